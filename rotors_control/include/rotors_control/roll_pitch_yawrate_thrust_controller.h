// RotorS' RollPitchYawrateThrustController API (RotorS' include/rotors_control/roll_pitch_yawrate_thrust_controller.h):
// roll and pitch [rad], yaw rate [rad/s] and thrust [N, thrust.z()] to rotor speeds. The law behind it is ours
// (AttitudeLevelController, attitude_controllers.h); names, fields and call order are RotorS'.
#pragma once

#include <memory>

#include <mav_msgs/conversions.h>
#include <mav_msgs/eigen_mav_msgs.h>

#include "rotors_control/common.h"
#include "rotors_control/parameters.h"
#include "rotors_control/rotors_api_gains.h"

namespace rotors_control {

class AttitudeLevelController;

class RollPitchYawrateThrustControllerParameters {
 public:
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
  RollPitchYawrateThrustControllerParameters()
      : attitude_gain_(kDefaultAttitudeGain), angular_rate_gain_(kDefaultAngularRateGain) {
    calculateAllocationMatrix(rotor_configuration_, &allocation_matrix_);
  }
  Eigen::Matrix4Xd allocation_matrix_;
  Eigen::Vector3d attitude_gain_;      ///< K_R
  Eigen::Vector3d angular_rate_gain_;  ///< K_omega
  RotorConfiguration rotor_configuration_;
};

class RollPitchYawrateThrustController {
 public:
  RollPitchYawrateThrustController();
  ~RollPitchYawrateThrustController();
  /// Throws std::invalid_argument naming a bad value.
  void InitializeParameters();
  /// Zeros until the first command; throws std::logic_error before InitializeParameters().
  void CalculateRotorVelocities(Eigen::VectorXd* rotor_velocities) const;
  void SetOdometry(const EigenOdometry& odometry);
  void SetRollPitchYawrateThrust(const mav_msgs::EigenRollPitchYawrateThrust& roll_pitch_yawrate_thrust);

  RollPitchYawrateThrustControllerParameters controller_parameters_;
  VehicleParameters vehicle_parameters_;
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW

 private:
  bool initialized_params_ = false;
  bool controller_active_ = false;
  std::unique_ptr<AttitudeLevelController> law_;
  mav_msgs::EigenRollPitchYawrateThrust roll_pitch_yawrate_thrust_;
  EigenOdometry odometry_;
};

}  // namespace rotors_control
