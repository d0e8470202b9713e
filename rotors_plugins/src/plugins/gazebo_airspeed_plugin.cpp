// librotors_gazebo_airspeed_plugin.so (ours): the book's wind sensor (section 4, eq. 19, Note 10) as
// geometry_msgs/Vector3Stamped on <ns>/<airspeedTopic> (default "air_speed"): v_air = v_wind - v of
// <linkName> in its own frame, the wind being what the wind plugin blows on this vehicle (its bus).
// <pitotAxis> (body axis, e.g. "1 0 0") makes it a pitot tube: only that component, along that
// axis. <noiseStdDev> [m/s], <randomEngineSeed>, <updateRate> [Hz] (0: every step).
#include <Eigen/Geometry>
#include <geometry_msgs/Vector3Stamped.h>

#include "rotors_gazebo_plugins/models/airspeed_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/link_sensor_plugin.h"
#include "rotors_gazebo_plugins/seeded_model.h"
#include "rotors_gazebo_plugins/ros/camera_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

class GazeboAirspeedPlugin : public LinkSensorPlugin<AirspeedReading, geometry_msgs::Vector3Stamped> {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    LoadLink(model, "airspeedTopic", "air_speed");
    AirspeedParams p;
    ReadParam(Params(), "noiseStdDev", &p.noise_stddev_m_s);
    ReadVector(Params(), "pitotAxis", &p.pitot_axis_B);
    double rate_hz = 0.0;
    ReadParam(Params(), "updateRate", &rate_hz);
    if (!(rate_hz >= 0.0)) throw rotors_sim::SimError("updateRate must be >= 0 Hz");
    ThrowIfInvalid(p.Validate());
    model_.Emplace(p, ReadSeed(Params()));
    limiter_ = RateLimiter(rate_hz);
    StartPublishing(Bus().sensors.airspeed);
  }

  void Reset() override { model_.Reset(); }

 private:
  void OnUpdate() override {
    const double t = world_->SimTime().Double();
    if (!limiter_.Due(t)) return;
    const auto X_WB = link_->WorldPose();
    const auto q = X_WB.Rot();
    const Eigen::Matrix3d R_WB = Eigen::Quaterniond(q.W(), q.X(), q.Y(), q.Z()).toRotationMatrix();
    const auto v = link_->WorldLinearVel();
    Put(AirspeedReading{model_->Measure(R_WB, Eigen::Vector3d(v.X(), v.Y(), v.Z()), Bus().wind_velocity_W)});
  }

  SeededModel<AirspeedModel> model_;
  RateLimiter limiter_{0.0};
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboAirspeedPlugin)
