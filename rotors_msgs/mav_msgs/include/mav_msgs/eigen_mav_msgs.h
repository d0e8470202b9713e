// Eigen counterparts of the mav_msgs messages, with the mav_comm API's names and frames
// (mav_comm's mav_msgs/include/mav_msgs/eigen_mav_msgs.h): _W world, _B body. Header-only.
#pragma once

#include <cstdint>
#include <deque>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/StdVector>

#include "mav_msgs/common.h"

namespace mav_msgs {

/// How many degrees of freedom a trajectory point commands: position and yaw, or full pose.
enum MavActuation { DOF4 = 4, DOF6 = 6 };

struct EigenAttitudeThrust {
  EigenAttitudeThrust() : attitude(Eigen::Quaterniond::Identity()), thrust(Eigen::Vector3d::Zero()) {}
  EigenAttitudeThrust(const Eigen::Quaterniond& _attitude, const Eigen::Vector3d& _thrust)
      : attitude(_attitude), thrust(_thrust) {}
  Eigen::Quaterniond attitude;
  Eigen::Vector3d thrust;  ///< [N], body frame
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct EigenActuators {
  EigenActuators() = default;
  EigenActuators(const Eigen::VectorXd& _angular_velocities) : angular_velocities(_angular_velocities) {}
  EigenActuators(const Eigen::VectorXd& _angles, const Eigen::VectorXd& _angular_velocities,
                 const Eigen::VectorXd& _normalized)
      : angles(_angles), angular_velocities(_angular_velocities), normalized(_normalized) {}
  Eigen::VectorXd angles;              ///< [rad]
  Eigen::VectorXd angular_velocities;  ///< [rad/s]
  Eigen::VectorXd normalized;          ///< [-1, 1]
};

struct EigenRateThrust {
  EigenRateThrust() : angular_rates(Eigen::Vector3d::Zero()), thrust(Eigen::Vector3d::Zero()) {}
  EigenRateThrust(const Eigen::Vector3d& _angular_rates, const Eigen::Vector3d _thrust)
      : angular_rates(_angular_rates), thrust(_thrust) {}
  Eigen::Vector3d angular_rates;  ///< [rad/s], body frame
  Eigen::Vector3d thrust;         ///< [N], body frame
};

struct EigenTorqueThrust {
  EigenTorqueThrust() : torque(Eigen::Vector3d::Zero()), thrust(Eigen::Vector3d::Zero()) {}
  EigenTorqueThrust(const Eigen::Vector3d& _torque, const Eigen::Vector3d _thrust) : torque(_torque), thrust(_thrust) {}
  Eigen::Vector3d torque;  ///< [Nm], body frame
  Eigen::Vector3d thrust;  ///< [N], body frame
};

struct EigenRollPitchYawrateThrust {
  EigenRollPitchYawrateThrust() : roll(0.0), pitch(0.0), yaw_rate(0.0), thrust(Eigen::Vector3d::Zero()) {}
  EigenRollPitchYawrateThrust(double _roll, double _pitch, double _yaw_rate, const Eigen::Vector3d& _thrust)
      : roll(_roll), pitch(_pitch), yaw_rate(_yaw_rate), thrust(_thrust) {}
  double roll;             ///< [rad]
  double pitch;            ///< [rad]
  double yaw_rate;         ///< [rad/s]
  Eigen::Vector3d thrust;  ///< [N], body frame
};

/// The full state of a MAV: the result of differential flatness, or what an estimator holds.
class EigenMavState {
 public:
  EigenMavState()
      : position_W(Eigen::Vector3d::Zero()),
        velocity_W(Eigen::Vector3d::Zero()),
        acceleration_B(Eigen::Vector3d::Zero()),
        orientation_W_B(Eigen::Quaterniond::Identity()),
        angular_velocity_B(Eigen::Vector3d::Zero()),
        angular_acceleration_B(Eigen::Vector3d::Zero()) {}
  EigenMavState(const Eigen::Vector3d& position_W, const Eigen::Vector3d& velocity_W,
                const Eigen::Vector3d& acceleration_B, const Eigen::Quaterniond& orientation_W_B,
                const Eigen::Vector3d& angular_velocity_B, const Eigen::Vector3d& angular_acceleration_B)
      : position_W(position_W),
        velocity_W(velocity_W),
        acceleration_B(acceleration_B),
        orientation_W_B(orientation_W_B),
        angular_velocity_B(angular_velocity_B),
        angular_acceleration_B(angular_acceleration_B) {}

  std::string toString() const {
    std::stringstream ss;
    ss << std::fixed << std::setprecision(3) << "position:              " << position_W.transpose() << "\n"
       << "velocity:              " << velocity_W.transpose() << "\n"
       << "acceleration_body:     " << acceleration_B.transpose() << "\n"
       << "orientation (w-x-y-z): " << orientation_W_B.w() << " " << orientation_W_B.vec().transpose() << "\n"
       << "angular_velocity_body: " << angular_velocity_B.transpose() << "\n"
       << "angular_acceleration_body: " << angular_acceleration_B.transpose() << "\n";
    return ss.str();
  }

  Eigen::Vector3d position_W;
  Eigen::Vector3d velocity_W;
  Eigen::Vector3d acceleration_B;
  Eigen::Quaterniond orientation_W_B;
  Eigen::Vector3d angular_velocity_B;
  Eigen::Vector3d angular_acceleration_B;
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct EigenTrajectoryPoint {
  EigenTrajectoryPoint()
      : timestamp_ns(-1),
        time_from_start_ns(0),
        position_W(Eigen::Vector3d::Zero()),
        velocity_W(Eigen::Vector3d::Zero()),
        acceleration_W(Eigen::Vector3d::Zero()),
        jerk_W(Eigen::Vector3d::Zero()),
        snap_W(Eigen::Vector3d::Zero()),
        orientation_W_B(Eigen::Quaterniond::Identity()),
        angular_velocity_W(Eigen::Vector3d::Zero()),
        angular_acceleration_W(Eigen::Vector3d::Zero()),
        degrees_of_freedom(MavActuation::DOF4) {}

  EigenTrajectoryPoint(int64_t _time_from_start_ns, const Eigen::Vector3d& _position, const Eigen::Vector3d& _velocity,
                       const Eigen::Vector3d& _acceleration, const Eigen::Vector3d& _jerk, const Eigen::Vector3d& _snap,
                       const Eigen::Quaterniond& _orientation, const Eigen::Vector3d& _angular_velocity,
                       const Eigen::Vector3d& _angular_acceleration,
                       const MavActuation& _degrees_of_freedom = MavActuation::DOF4)
      : timestamp_ns(-1),
        time_from_start_ns(_time_from_start_ns),
        position_W(_position),
        velocity_W(_velocity),
        acceleration_W(_acceleration),
        jerk_W(_jerk),
        snap_W(_snap),
        orientation_W_B(_orientation),
        angular_velocity_W(_angular_velocity),
        angular_acceleration_W(_angular_acceleration),
        degrees_of_freedom(_degrees_of_freedom) {}

  int64_t timestamp_ns;  ///< -1: not set
  int64_t time_from_start_ns;
  Eigen::Vector3d position_W;
  Eigen::Vector3d velocity_W;
  Eigen::Vector3d acceleration_W;
  Eigen::Vector3d jerk_W;
  Eigen::Vector3d snap_W;
  Eigen::Quaterniond orientation_W_B;
  Eigen::Vector3d angular_velocity_W;
  Eigen::Vector3d angular_acceleration_W;
  MavActuation degrees_of_freedom;

  double getYaw() const { return yawFromQuaternion(orientation_W_B); }
  double getYawRate() const { return angular_velocity_W.z(); }
  double getYawAcc() const { return angular_acceleration_W.z(); }
  /// Sets a yaw-only orientation (roll and pitch are dropped).
  void setFromYaw(double yaw) { orientation_W_B = quaternionFromYaw(yaw); }
  void setFromYawRate(double yaw_rate) { angular_velocity_W = {0.0, 0.0, yaw_rate}; }
  void setFromYawAcc(double yaw_acc) { angular_acceleration_W = {0.0, 0.0, yaw_acc}; }

  bool isApprox(const EigenTrajectoryPoint& other, double tolerance) const {
    return timestamp_ns == other.timestamp_ns && time_from_start_ns == other.time_from_start_ns &&
           position_W.isApprox(other.position_W, tolerance) && velocity_W.isApprox(other.velocity_W, tolerance) &&
           acceleration_W.isApprox(other.acceleration_W, tolerance) && jerk_W.isApprox(other.jerk_W, tolerance) &&
           snap_W.isApprox(other.snap_W, tolerance) && orientation_W_B.isApprox(other.orientation_W_B, tolerance) &&
           angular_velocity_W.isApprox(other.angular_velocity_W, tolerance) &&
           angular_acceleration_W.isApprox(other.angular_acceleration_W, tolerance) &&
           degrees_of_freedom == other.degrees_of_freedom;
  }
  bool operator==(const EigenTrajectoryPoint& rhs) const {
    return timestamp_ns == rhs.timestamp_ns && time_from_start_ns == rhs.time_from_start_ns &&
           position_W == rhs.position_W && velocity_W == rhs.velocity_W && acceleration_W == rhs.acceleration_W &&
           jerk_W == rhs.jerk_W && snap_W == rhs.snap_W && orientation_W_B.coeffs() == rhs.orientation_W_B.coeffs() &&
           angular_velocity_W == rhs.angular_velocity_W && angular_acceleration_W == rhs.angular_acceleration_W &&
           degrees_of_freedom == rhs.degrees_of_freedom;
  }
  bool operator!=(const EigenTrajectoryPoint& rhs) const { return !operator==(rhs); }

  std::string toString() const {
    std::stringstream ss;
    ss << std::fixed << std::setprecision(3) << "position:     " << position_W.transpose() << "\n"
       << "velocity:     " << velocity_W.transpose() << "\n"
       << "acceleration: " << acceleration_W.transpose() << "\n"
       << "jerk:         " << jerk_W.transpose() << "\n"
       << "snap:         " << snap_W.transpose() << "\n"
       << "yaw:          " << getYaw() << "\n"
       << "yaw_rate:     " << getYawRate() << "\n"
       << "yaw_acc:      " << getYawAcc() << "\n";
    return ss.str();
  }
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

/// Rigid transform T_A_W applied to a point given in W: the point in A (positions, derivatives,
/// orientation and angular rates rotated).
inline EigenTrajectoryPoint operator*(const Eigen::Affine3d& T_A_W, const EigenTrajectoryPoint& point_W) {
  EigenTrajectoryPoint p = point_W;
  const Eigen::Matrix3d R = T_A_W.rotation();
  p.position_W = T_A_W * point_W.position_W;
  p.velocity_W = R * point_W.velocity_W;
  p.acceleration_W = R * point_W.acceleration_W;
  p.jerk_W = R * point_W.jerk_W;
  p.snap_W = R * point_W.snap_W;
  p.orientation_W_B = Eigen::Quaterniond(R) * point_W.orientation_W_B;
  p.angular_velocity_W = R * point_W.angular_velocity_W;
  p.angular_acceleration_W = R * point_W.angular_acceleration_W;
  return p;
}

/// A trajectory reference is a trajectory point (mav_comm's alias).
typedef EigenTrajectoryPoint EigenTrajectoryReference;

struct EigenOdometry {
  EigenOdometry()
      : timestamp_ns(-1),
        position_W(Eigen::Vector3d::Zero()),
        orientation_W_B(Eigen::Quaterniond::Identity()),
        velocity_B(Eigen::Vector3d::Zero()),
        angular_velocity_B(Eigen::Vector3d::Zero()) {
    pose_covariance_.setZero();
    twist_covariance_.setZero();
  }
  EigenOdometry(const Eigen::Vector3d& _position, const Eigen::Quaterniond& _orientation,
                const Eigen::Vector3d& _velocity_body, const Eigen::Vector3d& _angular_velocity)
      : timestamp_ns(-1),
        position_W(_position),
        orientation_W_B(_orientation),
        velocity_B(_velocity_body),
        angular_velocity_B(_angular_velocity) {
    pose_covariance_.setZero();
    twist_covariance_.setZero();
  }

  int64_t timestamp_ns;  ///< -1: not set
  Eigen::Vector3d position_W;
  Eigen::Quaterniond orientation_W_B;
  Eigen::Vector3d velocity_B;  ///< body frame (nav_msgs/Odometry's twist is in the child frame)
  Eigen::Vector3d angular_velocity_B;
  Eigen::Matrix<double, 6, 6> pose_covariance_;
  Eigen::Matrix<double, 6, 6> twist_covariance_;

  double getYaw() const { return yawFromQuaternion(orientation_W_B); }
  void getEulerAngles(Eigen::Vector3d* euler_angles) const {
    getEulerAnglesFromQuaternion(orientation_W_B, euler_angles);
  }
  double getYawRate() const { return angular_velocity_B.z(); }
  /// v_W = R_W_B v_B
  Eigen::Vector3d getVelocityWorld() const { return orientation_W_B * velocity_B; }
  /// v_B = R_W_B^T v_W
  void setVelocityWorld(const Eigen::Vector3d& velocity_world) {
    velocity_B = orientation_W_B.inverse() * velocity_world;
  }
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// Eigen-aligned containers, named as in mav_comm: <Type>Vector and <Type>Deque.
#define MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EIGEN_TYPE)                                        \
  typedef std::vector<EIGEN_TYPE, Eigen::aligned_allocator<EIGEN_TYPE>> EIGEN_TYPE##Vector; \
  typedef std::deque<EIGEN_TYPE, Eigen::aligned_allocator<EIGEN_TYPE>> EIGEN_TYPE##Deque;

MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EigenAttitudeThrust)
MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EigenActuators)
MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EigenRateThrust)
MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EigenTorqueThrust)
MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EigenRollPitchYawrateThrust)
MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EigenMavState)
MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EigenTrajectoryPoint)
MAV_MSGS_MAKE_ALIGNED_CONTAINERS(EigenOdometry)

}  // namespace mav_msgs
