#include "rotors_control/roll_pitch_yawrate_thrust_controller.h"

#include <stdexcept>

#include "rotors_control/attitude_controllers.h"
#include "rotors_control/rotors_api_conversions.h"

namespace rotors_control {

RollPitchYawrateThrustController::RollPitchYawrateThrustController() = default;
RollPitchYawrateThrustController::~RollPitchYawrateThrustController() = default;

void RollPitchYawrateThrustController::InitializeParameters() {
  calculateAllocationMatrix(vehicle_parameters_.rotor_configuration_, &controller_parameters_.allocation_matrix_);
  AttitudeControllerParameters p;
  p.attitude.attitude_gain = controller_parameters_.attitude_gain_;
  p.attitude.angular_rate_gain = controller_parameters_.angular_rate_gain_;
  p.vehicle = MultirotorFromRotorS(vehicle_parameters_);
  law_ = std::make_unique<AttitudeLevelController>(p);  // throws std::invalid_argument naming a bad value
  if (controller_active_) SetRollPitchYawrateThrust(roll_pitch_yawrate_thrust_);
  initialized_params_ = true;
}

void RollPitchYawrateThrustController::CalculateRotorVelocities(Eigen::VectorXd* rotor_velocities) const {
  assert(rotor_velocities != nullptr);
  if (!initialized_params_)
    throw std::logic_error(
        "RollPitchYawrateThrustController: call InitializeParameters() before CalculateRotorVelocities()");
  *rotor_velocities = law_->RotorSpeeds(VehicleStateFromRotorS(odometry_));  // zeros without a command
}

void RollPitchYawrateThrustController::SetOdometry(const EigenOdometry& odometry) { odometry_ = odometry; }

void RollPitchYawrateThrustController::SetRollPitchYawrateThrust(
    const mav_msgs::EigenRollPitchYawrateThrust& roll_pitch_yawrate_thrust) {
  roll_pitch_yawrate_thrust_ = roll_pitch_yawrate_thrust;
  controller_active_ = true;
  if (!law_) return;  // applied by InitializeParameters()
  const auto& c = roll_pitch_yawrate_thrust;
  law_->SetRollPitchYawrateThrust(c.roll, c.pitch, c.yaw_rate, c.thrust.z());
}

}  // namespace rotors_control
