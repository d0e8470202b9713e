// RotorS' rotors_control API (RotorS' include/rotors_control/common.h): default topics, the controllers' odometry type
// and the allocation matrix. Header-only; same names and behaviour as RotorS.
#pragma once

#include <cassert>
#include <cmath>
#include <iostream>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <mav_msgs/conversions.h>
#include <mav_msgs/default_topics.h>
#include <nav_msgs/Odometry.h>

#include "rotors_control/parameters.h"

namespace rotors_control {

static const std::string kDefaultNamespace = "";
static const std::string kDefaultCommandMotorSpeedTopic = mav_msgs::default_topics::COMMAND_ACTUATORS;
static const std::string kDefaultCommandMultiDofJointTrajectoryTopic = mav_msgs::default_topics::COMMAND_TRAJECTORY;
static const std::string kDefaultCommandRollPitchYawrateThrustTopic =
    mav_msgs::default_topics::COMMAND_ROLL_PITCH_YAWRATE_THRUST;
static const std::string kDefaultImuTopic = mav_msgs::default_topics::IMU;
static const std::string kDefaultOdometryTopic = mav_msgs::default_topics::ODOMETRY;

/// Odometry as the controllers take it: position and orientation in the world, velocity and
/// angular velocity in the body frame (as nav_msgs/Odometry's twist).
struct EigenOdometry {
  EigenOdometry()
      : position(Eigen::Vector3d::Zero()),
        orientation(Eigen::Quaterniond::Identity()),
        velocity(Eigen::Vector3d::Zero()),
        angular_velocity(Eigen::Vector3d::Zero()) {}
  EigenOdometry(const Eigen::Vector3d& _position, const Eigen::Quaterniond& _orientation,
                const Eigen::Vector3d& _velocity, const Eigen::Vector3d& _angular_velocity)
      : position(_position), orientation(_orientation), velocity(_velocity), angular_velocity(_angular_velocity) {}
  Eigen::Vector3d position;
  Eigen::Quaterniond orientation;
  Eigen::Vector3d velocity;  ///< body frame
  Eigen::Vector3d angular_velocity;
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

inline void eigenOdometryFromMsg(const nav_msgs::OdometryConstPtr& msg, EigenOdometry* odometry) {
  assert(odometry != nullptr);
  mav_msgs::EigenOdometry o;
  mav_msgs::eigenOdometryFromMsg(*msg, &o);
  *odometry = EigenOdometry(o.position_W, o.orientation_W_B, o.velocity_B, o.angular_velocity_B);
}

/// The 4 x N matrix A with (roll torque, pitch torque, yaw torque, thrust) = A n^2 for the squared
/// rotor speeds n^2: rotor i at angle a_i, arm l_i, k_F, k_M and direction d_i gives the column
/// (l sin a k_F, -l cos a k_F, -d k_F k_M, k_F). Prints a warning when A has rank < 4.
inline void calculateAllocationMatrix(const RotorConfiguration& rotor_configuration,
                                      Eigen::Matrix4Xd* allocation_matrix) {
  assert(allocation_matrix != nullptr);
  const auto& rotors = rotor_configuration.rotors;
  allocation_matrix->resize(4, static_cast<Eigen::Index>(rotors.size()));
  for (size_t i = 0; i < rotors.size(); ++i) {
    const Rotor& r = rotors[i];
    allocation_matrix->col(static_cast<Eigen::Index>(i)) << std::sin(r.angle) * r.arm_length * r.rotor_force_constant,
        -std::cos(r.angle) * r.arm_length * r.rotor_force_constant,
        -r.direction * r.rotor_force_constant * r.rotor_moment_constant, r.rotor_force_constant;
  }
  Eigen::FullPivLU<Eigen::Matrix4Xd> lu(*allocation_matrix);
  lu.setThreshold(1e-9);
  if (lu.rank() < 4)
    std::cout << "The rank of the allocation matrix is " << lu.rank()
              << ", it should have rank 4 for a fully controllable system: check the rotor configuration." << std::endl;
}

inline void skewMatrixFromVector(Eigen::Vector3d& vector, Eigen::Matrix3d* skew_matrix) {
  *skew_matrix = mav_msgs::skewMatrixFromVector(vector);
}

inline void vectorFromSkewMatrix(Eigen::Matrix3d& skew_matrix, Eigen::Vector3d* vector) {
  *vector = mav_msgs::vectorFromSkewMatrix(skew_matrix);
}

}  // namespace rotors_control
