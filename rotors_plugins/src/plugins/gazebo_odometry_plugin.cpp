// librotors_gazebo_odometry_plugin.so: the generic odometry / pose sensor of reference section 4.5
// (odometry, pose, pose_with_covariance, position, transform; noise, divisor, delay, outage map,
// TF). Fixed against RotorS: the outage map resolves package:// URLs and takes effect,
// unknownDelay is added as seconds, an empty queue is never read, and the seed can be set.
#include <deque>

#include <ros/package.h>

#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/odometry_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"
#include "rotors_gazebo_plugins/seeded_model.h"
#include "rotors_gazebo_plugins/ros/feed_publisher.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

/// "package://pkg/rest" -> <path of pkg>/rest; other paths unchanged.
std::string ResolvePackageUrl(const std::string& url) {
  const std::string prefix = "package://";
  if (url.compare(0, prefix.size(), prefix) != 0) return url;
  const std::string rest = url.substr(prefix.size());
  const std::string pkg = rest.substr(0, rest.find('/'));
  const std::string path = ros::package::getPath(pkg);
  if (path.empty()) throw rotors_sim::SimError("cannot resolve '" + url + "': package '" + pkg + "' not found");
  return path + rest.substr(pkg.size());
}

class GazeboOdometryPlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    const std::string ns = ReadRobotNamespace(Params());
    std::string link_name = "odometry_sensor_link", parent_frame = "world";
    OdometryTopics topics;
    ReadParam(Params(), "linkName", &link_name);
    ReadParam(Params(), "poseTopic", &topics.pose);
    ReadParam(Params(), "poseWithCovarianceTopic", &topics.pose_with_covariance);
    ReadParam(Params(), "positionTopic", &topics.position);
    ReadParam(Params(), "transformTopic", &topics.transform);
    ReadParam(Params(), "odometryTopic", &topics.odometry);
    ReadParam(Params(), "parentFrameId", &parent_frame);
    std::string child_frame = "odometry_sensor";
    ReadParam(Params(), "childFrameId", &child_frame);
    ReadParam(Params(), "measurementDivisor", &divisor_);
    ReadParam(Params(), "measurementDelay", &delay_steps_);
    ReadParam(Params(), "unknownDelay", &unknown_delay_s_);
    if (parent_frame != "world")
      throw rotors_sim::SimError("parentFrameId = '" + parent_frame + "' is not supported yet; use 'world'");
    if (divisor_ < 1) throw rotors_sim::SimError("measurementDivisor = " + std::to_string(divisor_) + " must be >= 1");
    if (delay_steps_ < 0)
      throw rotors_sim::SimError("measurementDelay = " + std::to_string(delay_steps_) + " must be >= 0");
    const OdometryNoiseParams noise = ReadOdometryNoise(Params());
    const uint64_t seed = ReadSeed(Params());
    noise_.Emplace(noise, seed);
    std::string image;
    double scale = 1.0;
    ReadParam(Params(), "covarianceImageScale", &scale);
    if (ReadParam(Params(), "covarianceImage", &image) && !image.empty()) {
      // a bare file name is one of rotors_gazebo/resource's maps, as RotorS reads it
      if (image.find('/') == std::string::npos) image = "package://rotors_gazebo/resource/" + image;
      try {
        outage_map_ = std::make_unique<OutageMap>(ResolvePackageUrl(image), scale);
      } catch (const std::runtime_error& e) {
        throw rotors_sim::SimError(std::string("covarianceImage: ") + e.what());
      }
    }
    link_ = RequireLink(model, link_name);
    world_ = model->GetWorldRaw();
    bus_ = VehicleBus::For(*world_, ns);
    feed_ = &bus_->sensors.odometry.Of(ResolveTopic(ns, topics.odometry));
    bus_->Register(this, OdometryRecord{topics.odometry, link_name, divisor_, delay_steps_, unknown_delay_s_,
                                        outage_map_ != nullptr, noise, seed});
    // the simulator already broadcasts world -> canonical link; do not send the same transform twice
    const bool broadcast_tf = child_frame != model->GetCanonicalLink()->GetName();
    publisher_.Start(*feed_, *world_, ns, topics, parent_frame, child_frame, noise_->PoseCovariance(),
                     noise_->TwistCovariance(), broadcast_tf);
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
  }

  void Reset() override {
    noise_.Reset();
    queue_.clear();
    step_ = 0;
  }

 private:
  struct Pending {
    long publish_at_step;
    double stamp_s;  ///< [s] sim time taken, plus unknownDelay
    OdometryMeasurement truth;
  };

  void OnUpdate() {
    const long step = step_++;
    if (step % divisor_ == 0) {
      const auto X_WS = link_->WorldPose();
      if (!outage_map_ || outage_map_->Available(X_WS.Pos().X(), X_WS.Pos().Y())) {
        OdometryMeasurement m;
        m.p_W = {X_WS.Pos().X(), X_WS.Pos().Y(), X_WS.Pos().Z()};
        m.q_WS = Eigen::Quaterniond(X_WS.Rot().W(), X_WS.Rot().X(), X_WS.Rot().Y(), X_WS.Rot().Z());
        const auto v = link_->RelativeLinearVel(), w = link_->RelativeAngularVel();
        m.v_S = {v.X(), v.Y(), v.Z()};
        m.omega_S = {w.X(), w.Y(), w.Z()};
        queue_.push_back({step + delay_steps_, StampS(), m});
      }
    }
    while (!queue_.empty() && queue_.front().publish_at_step <= step) {
      Publish(queue_.front());
      queue_.pop_front();
    }
  }

  /// A measurement's stamp: the sim time now plus unknownDelay (whole nanoseconds).
  double StampS() const {
    return (world_->SimTime() + rotors_sim::common::Time::FromSeconds(unknown_delay_s_)).Double();
  }

  /// The measurement with its noise on the bus (and from there on the topics).
  void Publish(const Pending& pending) { feed_->Put(noise_->Corrupt(pending.truth), pending.stamp_s); }

  int divisor_ = 1, delay_steps_ = 0;
  double unknown_delay_s_ = 0.0;
  long step_ = 0;
  SeededModel<OdometryNoise> noise_;
  std::unique_ptr<OutageMap> outage_map_;
  std::deque<Pending> queue_;
  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  std::shared_ptr<VehicleBus> bus_;
  SensorFeed<OdometryMeasurement>* feed_ = nullptr;  ///< on the bus
  OdometryFeedPublisher publisher_;                  ///< the feed's readings on the five topics and TF
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboOdometryPlugin)
