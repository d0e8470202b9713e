// librotors_gazebo_odometry_plugin.so: the generic odometry / pose sensor of reference section 4.5
// (odometry, pose, pose_with_covariance, position, transform; noise, divisor, delay, outage map,
// TF). Fixed against RotorS: the outage map resolves package:// URLs and takes effect,
// unknownDelay is added as seconds, an empty queue is never read, and the seed can be set.
#include <deque>

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/PointStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/package.h>
#include <tf2_ros/transform_broadcaster.h>

#include "rotors_core/ros/publish_counts.h"
#include "rotors_core/ros/listened_publisher.h"
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
    std::string pose_topic = "pose", pose_cov_topic = "pose_with_covariance", position_topic = "position",
                transform_topic = "transform", odometry_topic = "odometry";
    ReadParam(Params(), "linkName", &link_name);
    ReadParam(Params(), "poseTopic", &pose_topic);
    ReadParam(Params(), "poseWithCovarianceTopic", &pose_cov_topic);
    ReadParam(Params(), "positionTopic", &position_topic);
    ReadParam(Params(), "transformTopic", &transform_topic);
    ReadParam(Params(), "odometryTopic", &odometry_topic);
    ReadParam(Params(), "parentFrameId", &parent_frame);
    ReadParam(Params(), "childFrameId", &child_frame_);
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
    // the simulator already broadcasts world -> canonical link; do not send the same transform twice
    broadcast_tf_ = child_frame_ != model->GetCanonicalLink()->GetName();
    parent_frame_ = parent_frame;

    node_ = MakeNode(ns);
    pose_pub_ = Advertise<geometry_msgs::Pose>(node_, ns, pose_topic, *model->GetWorldRaw(), 10);
    pose_cov_pub_ =
        Advertise<geometry_msgs::PoseWithCovarianceStamped>(node_, ns, pose_cov_topic, *model->GetWorldRaw(), 10);
    position_pub_ = Advertise<geometry_msgs::PointStamped>(node_, ns, position_topic, *model->GetWorldRaw(), 10);
    transform_pub_ = Advertise<geometry_msgs::TransformStamped>(node_, ns, transform_topic, *model->GetWorldRaw(), 10);
    odometry_pub_ = Advertise<nav_msgs::Odometry>(node_, ns, odometry_topic, *model->GetWorldRaw(), 10);
    bus_ = VehicleBus::For(*world_, ns);
    feed_ = &bus_->sensors.odometry.Of(ResolveTopic(ns, odometry_topic));
    bus_->Register(this, OdometryRecord{odometry_topic, link_name, divisor_, delay_steps_, unknown_delay_s_,
                                        outage_map_ != nullptr, noise, seed});
    if (node_) {
      if (broadcast_tf_) tf_ = std::make_unique<tf2_ros::TransformBroadcaster>();
    }
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
    ros::Time stamp;
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
        queue_.push_back({step + delay_steps_, ToRos(world_->SimTime()) + ros::Duration(unknown_delay_s_), m});
      }
    }
    while (!queue_.empty() && queue_.front().publish_at_step <= step) {
      Publish(queue_.front());
      queue_.pop_front();
    }
  }

  void Publish(const Pending& pending) {
    const OdometryMeasurement m = noise_->Corrupt(pending.truth);
    feed_->Put(m, pending.stamp.toSec());
    if (!odometry_pub_) return;  // neither ROS nor in-process taps
    geometry_msgs::Pose pose;
    pose.position.x = m.p_W.x();
    pose.position.y = m.p_W.y();
    pose.position.z = m.p_W.z();
    pose.orientation.w = m.q_WS.w();
    pose.orientation.x = m.q_WS.x();
    pose.orientation.y = m.q_WS.y();
    pose.orientation.z = m.q_WS.z();
    std_msgs::Header header;
    header.stamp = pending.stamp;
    header.frame_id = parent_frame_;
    if (pose_pub_.getNumSubscribers() > 0) pose_pub_.publish(pose);
    if (pose_cov_pub_.getNumSubscribers() > 0) {
      geometry_msgs::PoseWithCovarianceStamped msg;
      msg.header = header;
      msg.pose.pose = pose;
      const auto cov = noise_->PoseCovariance();
      std::copy(cov.begin(), cov.end(), msg.pose.covariance.begin());
      pose_cov_pub_.publish(msg);
    }
    if (position_pub_.getNumSubscribers() > 0) {
      geometry_msgs::PointStamped msg;
      msg.header = header;
      msg.point = pose.position;
      position_pub_.publish(msg);
    }
    geometry_msgs::TransformStamped tf;
    tf.header = header;
    tf.child_frame_id = child_frame_;
    tf.transform.translation.x = pose.position.x;
    tf.transform.translation.y = pose.position.y;
    tf.transform.translation.z = pose.position.z;
    tf.transform.rotation = pose.orientation;
    if (transform_pub_.getNumSubscribers() > 0) transform_pub_.publish(tf);
    if (tf_) tf_->sendTransform(tf);
    if (odometry_pub_.getNumSubscribers() > 0) {
      nav_msgs::Odometry msg;
      msg.header = header;
      msg.child_frame_id = child_frame_;
      msg.pose.pose = pose;
      const auto pose_cov = noise_->PoseCovariance();
      std::copy(pose_cov.begin(), pose_cov.end(), msg.pose.covariance.begin());
      msg.twist.twist.linear = ToVector3Msg(m.v_S);  // body (child) frame, as RotorS
      msg.twist.twist.angular = ToVector3Msg(m.omega_S);
      const auto twist_cov = noise_->TwistCovariance();
      std::copy(twist_cov.begin(), twist_cov.end(), msg.twist.covariance.begin());
      odometry_pub_.publish(msg);  // as a shared copy (ListenedPublisher): a controller nodelet gets it at once
    }
  }

  std::string child_frame_ = "odometry_sensor", parent_frame_ = "world";
  int divisor_ = 1, delay_steps_ = 0;
  double unknown_delay_s_ = 0.0;
  long step_ = 0;
  bool broadcast_tf_ = true;
  SeededModel<OdometryNoise> noise_;
  std::unique_ptr<OutageMap> outage_map_;
  std::deque<Pending> queue_;
  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  std::shared_ptr<ros::NodeHandle> node_;
  // ListenedPublisher: no search through every topic per step
  rotors_sim::ListenedPublisher pose_pub_, pose_cov_pub_, position_pub_, transform_pub_, odometry_pub_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_;
  std::shared_ptr<VehicleBus> bus_;
  SensorFeed<OdometryMeasurement>* feed_ = nullptr;  ///< on the bus
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboOdometryPlugin)
