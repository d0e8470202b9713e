#include "rotors_control/lee_position_controller.h"

#include <stdexcept>

#include "rotors_control/lee_controller.h"
#include "rotors_control/rotors_api_conversions.h"

namespace rotors_control {

LeePositionController::LeePositionController() = default;
LeePositionController::~LeePositionController() = default;

void LeePositionController::InitializeParameters() {
  calculateAllocationMatrix(vehicle_parameters_.rotor_configuration_, &controller_parameters_.allocation_matrix_);
  LeeControllerParameters p;
  p.position_gain = controller_parameters_.position_gain_;
  p.velocity_gain = controller_parameters_.velocity_gain_;
  p.attitude.attitude_gain = controller_parameters_.attitude_gain_;
  p.attitude.angular_rate_gain = controller_parameters_.angular_rate_gain_;
  p.vehicle = MultirotorFromRotorS(vehicle_parameters_);
  law_ = std::make_unique<LeeController>(p);  // throws std::invalid_argument naming a bad value
  if (controller_active_) SetTrajectoryPoint(command_trajectory_);
  initialized_params_ = true;
}

void LeePositionController::CalculateRotorVelocities(Eigen::VectorXd* rotor_velocities) const {
  assert(rotor_velocities != nullptr);
  if (!initialized_params_)
    throw std::logic_error("LeePositionController: call InitializeParameters() before CalculateRotorVelocities()");
  *rotor_velocities = law_->RotorSpeeds(VehicleStateFromRotorS(odometry_));  // zeros without a reference
}

void LeePositionController::SetOdometry(const EigenOdometry& odometry) { odometry_ = odometry; }

void LeePositionController::SetTrajectoryPoint(const mav_msgs::EigenTrajectoryPoint& command_trajectory) {
  command_trajectory_ = command_trajectory;
  controller_active_ = true;
  if (!law_) return;  // applied by InitializeParameters()
  law_->SetTrajectoryPoint(TrajectoryPointFromEigen(command_trajectory));
}

}  // namespace rotors_control
