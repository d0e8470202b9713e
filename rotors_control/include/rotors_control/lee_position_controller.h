// RotorS' LeePositionController API (RotorS' include/rotors_control/lee_position_controller.h): set the parameters'
// public fields (or keep the Firefly defaults), call InitializeParameters(), then SetOdometry / SetTrajectoryPoint /
// CalculateRotorVelocities. The law behind it is ours (LeeController, lee_controller.h, with
// RotorS' defects fixed); names, fields, units and call order are RotorS'.
#pragma once

#include <memory>

#include <mav_msgs/conversions.h>
#include <mav_msgs/eigen_mav_msgs.h>

#include "rotors_control/common.h"
#include "rotors_control/parameters.h"
#include "rotors_control/rotors_api_gains.h"

namespace rotors_control {

class LeeController;

static const Eigen::Vector3d kDefaultPositionGain = Eigen::Vector3d(6, 6, 6);
static const Eigen::Vector3d kDefaultVelocityGain = Eigen::Vector3d(4.7, 4.7, 4.7);

class LeePositionControllerParameters {
 public:
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
  LeePositionControllerParameters()
      : position_gain_(kDefaultPositionGain),
        velocity_gain_(kDefaultVelocityGain),
        attitude_gain_(kDefaultAttitudeGain),
        angular_rate_gain_(kDefaultAngularRateGain) {
    calculateAllocationMatrix(rotor_configuration_, &allocation_matrix_);
  }
  Eigen::Matrix4Xd allocation_matrix_;
  Eigen::Vector3d position_gain_;      ///< K_p
  Eigen::Vector3d velocity_gain_;      ///< K_v
  Eigen::Vector3d attitude_gain_;      ///< K_R
  Eigen::Vector3d angular_rate_gain_;  ///< K_omega
  RotorConfiguration rotor_configuration_;
};

class LeePositionController {
 public:
  LeePositionController();
  ~LeePositionController();
  /// Builds the controller from controller_parameters_ and vehicle_parameters_ (their allocation
  /// matrix from vehicle_parameters_.rotor_configuration_). Throws std::invalid_argument naming a
  /// bad value (a non-positive mass, say).
  void InitializeParameters();
  /// Rotor speeds [rad/s], one per rotor; zeros until the first trajectory point. Throws
  /// std::logic_error before InitializeParameters().
  void CalculateRotorVelocities(Eigen::VectorXd* rotor_velocities) const;
  void SetOdometry(const EigenOdometry& odometry);
  void SetTrajectoryPoint(const mav_msgs::EigenTrajectoryPoint& command_trajectory);

  LeePositionControllerParameters controller_parameters_;
  VehicleParameters vehicle_parameters_;
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW

 private:
  bool initialized_params_ = false;
  bool controller_active_ = false;
  std::unique_ptr<LeeController> law_;
  mav_msgs::EigenTrajectoryPoint command_trajectory_;
  EigenOdometry odometry_;
};

}  // namespace rotors_control
