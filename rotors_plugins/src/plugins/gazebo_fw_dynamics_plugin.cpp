// librotors_gazebo_fw_dynamics_plugin.so: RotorS' fixed-wing dynamics (FixedWingModel) on <linkName>:
// each step the airspeed (link velocity minus the vehicle's wind, from its bus) and the body rates
// give the aerodynamic and thrust wrench, applied at the link's CoG; the air's density is the
// standard atmosphere's at the link's altitude (the world's elevation plus its height; RotorS: 1.18). Inputs, held
// between messages (all 0 at the start):
// - <actuatorsSubTopic> (default command/motor_speed): mav_msgs/Actuators, field normalized, by the
//   channels of <vehicleParamsYAML>;
// - with <isInputJoystick> true, <rollPitchYawrateThrustSubTopic> (default
//   command/roll_pitch_yawrate_thrust): roll -> left aileron, -roll -> right aileron, pitch ->
//   elevator, yaw_rate -> rudder, thrust.x -> throttle (flap 0), RotorS' joystick mapping;
// - in process (the Python module): VehicleBus::SetNormalizedCommand.
// <aeroParamsYAML> and <vehicleParamsYAML> are required (RotorS falls back to built-in techpod values
// with a warning; here a missing file is an error naming it). <windSpeedSubTopic> is accepted: the
// wind comes from the vehicle's bus (the wind plugin), not from a topic.
#include <memory>

#include <mav_msgs/Actuators.h>
#include <mav_msgs/RollPitchYawrateThrust.h>

#include "rotors_core/error.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/fixed_wing_model.h"
#include "rotors_gazebo_plugins/models/standard_atmosphere.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"

namespace rotors_gazebo_plugins {

class GazeboFwDynamicsPlugin : public rotors_sim::ModelPlugin {
 public:
  void Load(rotors_sim::physics::ModelPtr model, sdf::ElementPtr /*sdf*/) override {
    namespace_ = ReadRobotNamespace(Params());
    std::string link_name, aero_yaml, vehicle_yaml;
    RequireParam(Params(), "linkName", &link_name);
    RequireParam(Params(), "aeroParamsYAML", &aero_yaml);
    RequireParam(Params(), "vehicleParamsYAML", &vehicle_yaml);
    bool joystick = false;
    ReadParam(Params(), "isInputJoystick", &joystick);
    std::string actuators_topic = "command/motor_speed", rpyt_topic = "command/roll_pitch_yawrate_thrust";
    ReadParam(Params(), "actuatorsSubTopic", &actuators_topic);
    ReadParam(Params(), "rollPitchYawrateThrustSubTopic", &rpyt_topic);
    Params().Accept("windSpeedSubTopic", "the wind comes from the vehicle's bus (the wind plugin)");
    try {
      model_ = std::make_unique<FixedWingModel>(FixedWingAeroParams::FromYaml(aero_yaml),
                                                FixedWingVehicleParams::FromYaml(vehicle_yaml));
    } catch (const std::exception& e) {
      throw rotors_sim::SimError(e.what());
    }
    link_ = RequireLink(model, link_name);
    bus_ = VehicleBus::For(*model->GetWorldRaw(), namespace_);
    elevation_m_ = model->GetWorldRaw()->Origin().elevation_m;
    const FixedWingVehicleParams& v = model_->Vehicle();
    for (int channel : {v.aileron_left.channel, v.aileron_right.channel, v.elevator.channel, v.flap.channel,
                        v.rudder.channel, v.throttle_channel})
      bus_->normalized_channels = std::max(bus_->normalized_channels, channel + 1);
    // every command (ROS or in process) is checked on the way in: deflections in range, throttle 0..1
    bus_->normalized_check = [this](const std::vector<double>& normalized) {
      FixedWingInputs checked;
      return FixedWingInputs::FromNormalized(normalized, model_->Vehicle(), &checked);
    };
    node_ = MakeNode(namespace_);
    if (node_) {
      if (joystick) sub_ = node_->subscribe(rpyt_topic, 1, &GazeboFwDynamicsPlugin::OnRollPitchYawrateThrust, this);
      else sub_ = node_->subscribe(actuators_topic, 1, &GazeboFwDynamicsPlugin::OnActuators, this);
    }
    connection_ = rotors_sim::event::Events::ConnectWorldUpdateBegin(
        [this](const rotors_sim::common::UpdateInfo&) { OnUpdate(); });
  }

  ~GazeboFwDynamicsPlugin() override {
    if (bus_) bus_->normalized_check = nullptr;  // the bus may outlive this plugin (another holds it)
  }

  void Reset() override {
    inputs_ = FixedWingInputs{};
    bus_->normalized_command.clear();
    seen_ = bus_->normalized_command_count;
  }

  const FixedWingWrench& LastWrench() const { return last_; }

 private:
  void Submit(const std::vector<double>& normalized) {
    const std::string why = bus_->SetNormalizedCommand(normalized);
    if (!why.empty())
      ROS_ERROR_THROTTLE(1.0, "[fw_dynamics] %s: rejected command: %s; keeping the last valid one", namespace_.c_str(),
                         why.c_str());
  }
  void OnActuators(const mav_msgs::ActuatorsConstPtr& msg) { Submit(msg->normalized); }
  void OnRollPitchYawrateThrust(const mav_msgs::RollPitchYawrateThrustConstPtr& msg) {
    const FixedWingVehicleParams& v = model_->Vehicle();
    std::vector<double> normalized(bus_->normalized_channels, 0.0);
    normalized[v.aileron_left.channel] = msg->roll;
    normalized[v.aileron_right.channel] = -msg->roll;
    normalized[v.elevator.channel] = msg->pitch;
    normalized[v.rudder.channel] = msg->yaw_rate;
    normalized[v.throttle_channel] = msg->thrust.x;
    Submit(normalized);
  }

  void OnUpdate() {
    if (bus_->normalized_command_count != seen_) {  // a new command (ROS or in process), checked on the way in
      seen_ = bus_->normalized_command_count;
      FixedWingInputs::FromNormalized(bus_->normalized_command, model_->Vehicle(), &inputs_);
    }
    const auto X_WB = link_->WorldPose();
    const auto v_W = link_->WorldLinearVel();
    const Eigen::Vector3d& wind_W = bus_->wind_velocity_W;
    // v_air_B = R_WB^T (v_link_W - wind_W); omega in the body frame
    const auto v_air_B = X_WB.Rot().RotateVectorReverse(
        rotors_sim::physics::Vector3d(v_W.X() - wind_W.x(), v_W.Y() - wind_W.y(), v_W.Z() - wind_W.z()));
    const auto w_B = link_->RelativeAngularVel();
    // the standard atmosphere at the link's altitude (the world origin's elevation plus its height)
    const double rho = StandardAtmosphereDensity(elevation_m_ + X_WB.Pos().Z());
    last_ = model_->Compute({v_air_B.X(), v_air_B.Y(), v_air_B.Z()}, {w_B.X(), w_B.Y(), w_B.Z()}, inputs_, rho);
    link_->AddRelativeForce({last_.force_B.x(), last_.force_B.y(), last_.force_B.z()});
    link_->AddRelativeTorque({last_.moment_B.x(), last_.moment_B.y(), last_.moment_B.z()});
  }

  std::string namespace_;
  double elevation_m_ = 0.0;  ///< [m] of the world origin (<spherical_coordinates>)
  std::unique_ptr<FixedWingModel> model_;
  FixedWingInputs inputs_;
  FixedWingWrench last_;
  rotors_sim::physics::LinkPtr link_;
  std::shared_ptr<VehicleBus> bus_;
  uint64_t seen_ = 0;
  std::shared_ptr<ros::NodeHandle> node_;
  ros::Subscriber sub_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

GZ_REGISTER_MODEL_PLUGIN(rotors_gazebo_plugins::GazeboFwDynamicsPlugin)
