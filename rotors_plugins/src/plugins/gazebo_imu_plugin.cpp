// librotors_gazebo_imu_plugin.so: sensor_msgs/Imu on <ns>/<imuTopic> every physics step with the
// noise model of book eqs. 12-15 (reference section 4.4). Every parameter the RotorS xacro
// writes is read: <gyroscopeRandomWalk> (xacro spelling) and <gyroscopeBiasRandomWalk> (plugin
// spelling) are the same parameter (RotorS issue #336 does not recur).
// Ours: <biasTopic> (optional) publishes the true biases (rotors_comm/ImuBias) while someone
// listens, so estimators can be judged on their bias estimates. <rotorVibration> (default false)
// adds the rotors' vibration and samples as the ADIS16448 does (ImuVibrationModel): the rotors come
// from the vehicle bus, the mass and inertia from the rigid body the IMU is welded to.
#include <rotors_comm/ImuBias.h>

#include <Eigen/Geometry>

#include "rotors_core/ros/publish_counts.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/imu_noise_model.h"
#include "rotors_gazebo_plugins/models/imu_vibration_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/seeded_model.h"
#include "rotors_gazebo_plugins/ros/feed_publisher.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

namespace {
Eigen::Vector3d VectorOf(const ignition::math::Vector3d& v) { return {v.X(), v.Y(), v.Z()}; }
Eigen::Matrix3d RotationOf(const ignition::math::Quaterniond& q) {
  return Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z()).toRotationMatrix();
}
}  // namespace

class GazeboImuPlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    const std::string ns = ReadRobotNamespace(Params());
    std::string link_name, topic = "imu", bias_topic;
    RequireParam(Params(), "linkName", &link_name);
    ReadParam(Params(), "imuTopic", &topic);
    ReadParam(Params(), "biasTopic", &bias_topic);
    const ImuNoiseParams p = ReadImuNoise(Params());
    const uint64_t seed = ReadSeed(Params());
    noise_.Emplace(p, seed);

    link_ = RequireLink(model, link_name);
    world_ = model->GetWorldRaw();
    bus_ = VehicleBus::For(*world_, ns);
    feed_ = &bus_->sensors.imu.Of(ResolveTopic(ns, topic));
    const ImuVibrationParams vibration = ReadImuVibration(Params());
    if (vibration.enabled) LoadVibration(model, vibration, seed);
    bus_->Register(this, ImuRecord{link_name, p, vibration.enabled, seed});
    sensor_msgs::Imu prototype;
    prototype.header.frame_id = frame_id_ = link_name;
    prototype.orientation_covariance.fill(-1.0);  // orientation is ground truth (as RotorS), not a measurement
    for (int i = 0; i < 3; ++i) {
      prototype.angular_velocity_covariance[i * 4] = p.gyroscope_noise_density * p.gyroscope_noise_density;
      prototype.linear_acceleration_covariance[i * 4] = p.accelerometer_noise_density * p.accelerometer_noise_density;
    }
    publisher_.Start(*feed_, *world_, ns, topic, prototype);
    node_ = MakeNode(ns);
    if (!bias_topic.empty()) bias_pub_ = Advertise<rotors_comm::ImuBias>(node_, ns, bias_topic, *world_, 10);
    if (node_) {
      ROS_DEBUG("[imu] %s/%s seed %lu", ns.c_str(), topic.c_str(), static_cast<unsigned long>(seed));
    }
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnUpdate(); });
  }

  void Reset() override {
    noise_.Reset();
    vibration_.Reset();
    have_truth_ = false;
  }

 private:
  void OnUpdate() {
    const double dt = world_->Physics().max_step_size_s;
    const auto X_WI = link_->WorldPose();
    // specific force: f_I = R_WI^T (a_W - g_W)
    const auto f_I = X_WI.Rot().RotateVectorReverse(link_->WorldLinearAccel() - world_->Gravity());
    const auto w_I = link_->RelativeAngularVel();
    const ImuSample truth{{w_I.X(), w_I.Y(), w_I.Z()}, {f_I.X(), f_I.Y(), f_I.Z()}};
    const ImuSample m = noise_->Corrupt(vibration_ ? Vibrate(truth, dt) : truth, dt);
    const auto& q = X_WI.Rot();
    feed_->Put({m, Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z())}, world_->SimTime().Double());
    if (bias_pub_ && bias_pub_.getNumSubscribers() > 0) {
      rotors_comm::ImuBias bias;
      bias.header.stamp = StampOf(feed_->time_s);
      bias.header.frame_id = frame_id_;
      bias.gyroscope_bias = ToVector3Msg(noise_->TotalGyroscopeBias());
      bias.accelerometer_bias = ToVector3Msg(noise_->TotalAccelerometerBias());
      bias_pub_.publish(bias);
    }
  }

  void LoadVibration(const rotors_sim::physics::ModelPtr& model, const ImuVibrationParams& params, uint64_t seed) {
    VibratingBody body;
    bool found = false;
    for (const auto& b : model->BodyMasses())
      if (b.body == link_->Body()) {
        body.mass_kg = b.mass_kg;
        body.inertia_B_kg_m2 = b.inertia_B_kg_m2;
        found = true;
      }
    if (!found)
      throw rotors_sim::SimError("IMU '" + link_->GetName() +
                                 "': rotorVibration needs the IMU on a moving rigid body (it is static); "
                                 "set rotorVibration false");
    const auto& X_BI = link_->PoseInBody();
    body.p_B_imu = VectorOf(X_BI.Pos());
    body.R_BI = RotationOf(X_BI.Rot());
    ThrowIfInvalid(body.Validate());
    vibration_.Emplace(params, body, seed + 1);
  }

  /// The rotors on the IMU's rigid body as the vibration sees them now (tilting rotors move).
  const std::vector<VibratingRotor>& Rotors() {
    rotors_.clear();
    for (size_t i = 0; i < bus_->rotor_mountings.size(); ++i) {
      const RotorMounting& m = bus_->rotor_mountings[i];
      if (!m.link || m.link->Body() != link_->Body()) continue;
      const auto& X_BR = m.link->PoseInBody();
      VibratingRotor r;
      r.p_B = VectorOf(X_BR.Pos());
      r.axis_B = RotationOf(X_BR.Rot()) * m.axis_L;
      r.rotor_mass_kg = m.rotor_mass_kg;
      r.max_rot_velocity_rad_s = bus_->max_rot_velocity_rad_s[i];
      r.motor_constant = m.motor_constant;
      r.speed_rad_s = bus_->rotor_speed_rad_s[i];
      rotors_.push_back(r);
    }
    return rotors_;
  }

  ImuSample Vibrate(const ImuSample& truth, double dt) {
    if (!have_truth_) last_truth_ = truth, have_truth_ = true;
    const ImuSample read = vibration_->Step(last_truth_, truth, Rotors(), dt);
    last_truth_ = truth;
    return read;
  }

  SeededModel<ImuNoiseModel> noise_;
  SeededModel<ImuVibrationModel> vibration_;
  std::shared_ptr<VehicleBus> bus_;
  SensorFeed<ImuReading>* feed_ = nullptr;  ///< on the bus
  std::vector<VibratingRotor> rotors_;
  ImuSample last_truth_;
  bool have_truth_ = false;
  rotors_sim::physics::LinkPtr link_;
  rotors_sim::physics::World* world_ = nullptr;
  FeedPublisher<ImuReading, sensor_msgs::Imu> publisher_;  ///< the feed's readings on <imuTopic>
  std::string frame_id_;                                   ///< linkName
  std::shared_ptr<ros::NodeHandle> node_;
  rotors_sim::ListenedPublisher bias_pub_;  // no search through every topic per step
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboImuPlugin)
