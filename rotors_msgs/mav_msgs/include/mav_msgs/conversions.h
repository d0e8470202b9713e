// Messages <-> Eigen types of the mav_comm API (mav_comm's mav_msgs/include/mav_msgs/conversions.h). Header-only.
// Trajectory points: transforms[0], velocities[0] and accelerations[0] are used (velocities and
// accelerations are optional; zero when absent); jerk and snap have no field and read as zero.
#pragma once

#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "mav_msgs/Actuators.h"
#include "mav_msgs/AttitudeThrust.h"
#include "mav_msgs/RateThrust.h"
#include "mav_msgs/RollPitchYawrateThrust.h"
#include "mav_msgs/TorqueThrust.h"
#include "mav_msgs/common.h"
#include "mav_msgs/default_topics.h"
#include "mav_msgs/default_values.h"
#include "mav_msgs/eigen_mav_msgs.h"

namespace mav_msgs {

namespace internal {
inline Eigen::VectorXd VectorFromArray(const std::vector<double>& a) {
  return Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(a.size()));
}
inline std::vector<double> ArrayFromVector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }
/// A ROS covariance (36 numbers, row-major) into a 6 x 6 matrix and back.
inline Eigen::Matrix<double, 6, 6> MatrixFromCovariance(const boost::array<double, 36>& c) {
  return Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(c.data());
}
inline void CovarianceFromMatrix(const Eigen::Matrix<double, 6, 6>& m, boost::array<double, 36>* c) {
  Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(c->data()) = m;
}
inline ros::Time TimeFromNanoseconds(int64_t ns) {
  ros::Time t;
  if (ns >= 0) t.fromNSec(static_cast<uint64_t>(ns));
  return t;
}
}  // namespace internal

// ---- messages -> Eigen ------------------------------------------------------------------------

inline void eigenAttitudeThrustFromMsg(const AttitudeThrust& msg, EigenAttitudeThrust* attitude_thrust) {
  attitude_thrust->attitude = quaternionFromMsg(msg.attitude);
  attitude_thrust->thrust = vector3FromMsg(msg.thrust);
}

inline void eigenActuatorsFromMsg(const Actuators& msg, EigenActuators* actuators) {
  actuators->angles = internal::VectorFromArray(msg.angles);
  actuators->angular_velocities = internal::VectorFromArray(msg.angular_velocities);
  actuators->normalized = internal::VectorFromArray(msg.normalized);
}

inline void eigenRateThrustFromMsg(const RateThrust& msg, EigenRateThrust* rate_thrust) {
  rate_thrust->angular_rates = vector3FromMsg(msg.angular_rates);
  rate_thrust->thrust = vector3FromMsg(msg.thrust);
}

inline void eigenTorqueThrustFromMsg(const TorqueThrust& msg, EigenTorqueThrust* torque_thrust) {
  torque_thrust->torque = vector3FromMsg(msg.torque);
  torque_thrust->thrust = vector3FromMsg(msg.thrust);
}

inline void eigenRollPitchYawrateThrustFromMsg(const RollPitchYawrateThrust& msg,
                                               EigenRollPitchYawrateThrust* roll_pitch_yawrate_thrust) {
  roll_pitch_yawrate_thrust->roll = msg.roll;
  roll_pitch_yawrate_thrust->pitch = msg.pitch;
  roll_pitch_yawrate_thrust->yaw_rate = msg.yaw_rate;
  roll_pitch_yawrate_thrust->thrust = vector3FromMsg(msg.thrust);
}

/// The twist of nav_msgs/Odometry is in the child (body) frame: it becomes velocity_B.
inline void eigenOdometryFromMsg(const nav_msgs::Odometry& msg, EigenOdometry* odometry) {
  odometry->timestamp_ns = static_cast<int64_t>(msg.header.stamp.toNSec());
  odometry->position_W = vector3FromPointMsg(msg.pose.pose.position);
  odometry->orientation_W_B = quaternionFromMsg(msg.pose.pose.orientation);
  odometry->velocity_B = vector3FromMsg(msg.twist.twist.linear);
  odometry->angular_velocity_B = vector3FromMsg(msg.twist.twist.angular);
  odometry->pose_covariance_ = internal::MatrixFromCovariance(msg.pose.covariance);
  odometry->twist_covariance_ = internal::MatrixFromCovariance(msg.twist.covariance);
}

inline void eigenTrajectoryPointFromTransformMsg(const geometry_msgs::TransformStamped& msg,
                                                 EigenTrajectoryPoint* point) {
  *point = EigenTrajectoryPoint();
  point->timestamp_ns = static_cast<int64_t>(msg.header.stamp.toNSec());
  point->position_W = vector3FromMsg(msg.transform.translation);
  point->orientation_W_B = quaternionFromMsg(msg.transform.rotation);
}

inline void eigenTrajectoryPointFromPoseMsg(const geometry_msgs::Pose& msg, EigenTrajectoryPoint* point) {
  *point = EigenTrajectoryPoint();
  point->position_W = vector3FromPointMsg(msg.position);
  point->orientation_W_B = quaternionFromMsg(msg.orientation);
}

inline void eigenTrajectoryPointFromPoseMsg(const geometry_msgs::PoseStamped& msg, EigenTrajectoryPoint* point) {
  eigenTrajectoryPointFromPoseMsg(msg.pose, point);
  point->timestamp_ns = static_cast<int64_t>(msg.header.stamp.toNSec());
}

inline void eigenTrajectoryPointFromMsg(const trajectory_msgs::MultiDOFJointTrajectoryPoint& msg,
                                        EigenTrajectoryPoint* point) {
  if (msg.transforms.empty()) {
    ROS_ERROR("MultiDOFJointTrajectoryPoint is empty (no transforms); the trajectory point is left unchanged.");
    return;
  }
  if (msg.transforms.size() > 1)
    ROS_WARN("MultiDOFJointTrajectoryPoint with %zu transforms: only the first is used.", msg.transforms.size());
  *point = EigenTrajectoryPoint();
  point->time_from_start_ns = static_cast<int64_t>(msg.time_from_start.toNSec());
  point->position_W = vector3FromMsg(msg.transforms[0].translation);
  point->orientation_W_B = quaternionFromMsg(msg.transforms[0].rotation);
  if (!msg.velocities.empty()) {
    point->velocity_W = vector3FromMsg(msg.velocities[0].linear);
    point->angular_velocity_W = vector3FromMsg(msg.velocities[0].angular);
  }
  if (!msg.accelerations.empty()) {
    point->acceleration_W = vector3FromMsg(msg.accelerations[0].linear);
    point->angular_acceleration_W = vector3FromMsg(msg.accelerations[0].angular);
  }
}

/// Every point, with timestamp_ns = header stamp + time_from_start.
inline void eigenTrajectoryPointVectorFromMsg(const trajectory_msgs::MultiDOFJointTrajectory& msg,
                                              EigenTrajectoryPointVector* trajectory) {
  if (msg.points.empty()) ROS_WARN("MultiDOFJointTrajectory has no points.");
  trajectory->clear();
  for (const auto& msg_point : msg.points) {
    EigenTrajectoryPoint point;
    eigenTrajectoryPointFromMsg(msg_point, &point);
    point.timestamp_ns = static_cast<int64_t>(msg.header.stamp.toNSec()) + point.time_from_start_ns;
    trajectory->push_back(point);
  }
}

inline void eigenTrajectoryPointDequeFromMsg(const trajectory_msgs::MultiDOFJointTrajectory& msg,
                                             EigenTrajectoryPointDeque* trajectory) {
  EigenTrajectoryPointVector points;
  eigenTrajectoryPointVectorFromMsg(msg, &points);
  trajectory->assign(points.begin(), points.end());
}

// ---- Eigen -> messages ------------------------------------------------------------------------

inline void msgActuatorsFromEigen(const EigenActuators& actuators, Actuators* msg) {
  msg->angles = internal::ArrayFromVector(actuators.angles);
  msg->angular_velocities = internal::ArrayFromVector(actuators.angular_velocities);
  msg->normalized = internal::ArrayFromVector(actuators.normalized);
}

inline void msgAttitudeThrustFromEigen(const EigenAttitudeThrust& attitude_thrust, AttitudeThrust* msg) {
  quaternionEigenToMsg(attitude_thrust.attitude, &msg->attitude);
  vectorEigenToMsg(attitude_thrust.thrust, &msg->thrust);
}

inline void msgRateThrustFromEigen(const EigenRateThrust& rate_thrust, RateThrust* msg) {
  vectorEigenToMsg(rate_thrust.angular_rates, &msg->angular_rates);
  vectorEigenToMsg(rate_thrust.thrust, &msg->thrust);
}

inline void msgTorqueThrustFromEigen(const EigenTorqueThrust& torque_thrust, TorqueThrust* msg) {
  vectorEigenToMsg(torque_thrust.torque, &msg->torque);
  vectorEigenToMsg(torque_thrust.thrust, &msg->thrust);
}

inline void msgRollPitchYawrateThrustFromEigen(const EigenRollPitchYawrateThrust& roll_pitch_yawrate_thrust,
                                               RollPitchYawrateThrust* msg) {
  msg->roll = roll_pitch_yawrate_thrust.roll;
  msg->pitch = roll_pitch_yawrate_thrust.pitch;
  msg->yaw_rate = roll_pitch_yawrate_thrust.yaw_rate;
  vectorEigenToMsg(roll_pitch_yawrate_thrust.thrust, &msg->thrust);
}

inline void msgOdometryFromEigen(const EigenOdometry& odometry, nav_msgs::Odometry* msg) {
  if (odometry.timestamp_ns >= 0) msg->header.stamp = internal::TimeFromNanoseconds(odometry.timestamp_ns);
  pointEigenToMsg(odometry.position_W, &msg->pose.pose.position);
  quaternionEigenToMsg(odometry.orientation_W_B, &msg->pose.pose.orientation);
  vectorEigenToMsg(odometry.velocity_B, &msg->twist.twist.linear);
  vectorEigenToMsg(odometry.angular_velocity_B, &msg->twist.twist.angular);
  internal::CovarianceFromMatrix(odometry.pose_covariance_, &msg->pose.covariance);
  internal::CovarianceFromMatrix(odometry.twist_covariance_, &msg->twist.covariance);
}

inline void msgPoseStampedFromEigenTrajectoryPoint(const EigenTrajectoryPoint& point, geometry_msgs::PoseStamped* msg) {
  if (point.timestamp_ns >= 0) msg->header.stamp = internal::TimeFromNanoseconds(point.timestamp_ns);
  pointEigenToMsg(point.position_W, &msg->pose.position);
  quaternionEigenToMsg(point.orientation_W_B, &msg->pose.orientation);
}

inline void msgMultiDofJointTrajectoryPointFromEigen(const EigenTrajectoryPoint& point,
                                                     trajectory_msgs::MultiDOFJointTrajectoryPoint* msg) {
  msg->time_from_start.fromNSec(static_cast<uint64_t>(std::max<int64_t>(point.time_from_start_ns, 0)));
  msg->transforms.resize(1);
  msg->velocities.resize(1);
  msg->accelerations.resize(1);
  vectorEigenToMsg(point.position_W, &msg->transforms[0].translation);
  quaternionEigenToMsg(point.orientation_W_B, &msg->transforms[0].rotation);
  vectorEigenToMsg(point.velocity_W, &msg->velocities[0].linear);
  vectorEigenToMsg(point.angular_velocity_W, &msg->velocities[0].angular);
  vectorEigenToMsg(point.acceleration_W, &msg->accelerations[0].linear);
  vectorEigenToMsg(point.angular_acceleration_W, &msg->accelerations[0].angular);
}

/// One point for the joint `link_name`.
inline void msgMultiDofJointTrajectoryFromEigen(const EigenTrajectoryPoint& point, const std::string& link_name,
                                                trajectory_msgs::MultiDOFJointTrajectory* msg) {
  if (point.timestamp_ns >= 0) msg->header.stamp = internal::TimeFromNanoseconds(point.timestamp_ns);
  msg->joint_names = {link_name};
  msg->points.resize(1);
  msgMultiDofJointTrajectoryPointFromEigen(point, &msg->points[0]);
}

inline void msgMultiDofJointTrajectoryFromEigen(const EigenTrajectoryPoint& point,
                                                trajectory_msgs::MultiDOFJointTrajectory* msg) {
  msgMultiDofJointTrajectoryFromEigen(point, "base_link", msg);
}

/// All points, stamped with the first point's timestamp.
inline void msgMultiDofJointTrajectoryFromEigen(const EigenTrajectoryPointVector& trajectory,
                                                const std::string& link_name,
                                                trajectory_msgs::MultiDOFJointTrajectory* msg) {
  msg->points.clear();
  msg->joint_names = {link_name};
  if (trajectory.empty()) return;
  if (trajectory.front().timestamp_ns >= 0)
    msg->header.stamp = internal::TimeFromNanoseconds(trajectory.front().timestamp_ns);
  msg->points.resize(trajectory.size());
  for (size_t i = 0; i < trajectory.size(); ++i)
    msgMultiDofJointTrajectoryPointFromEigen(trajectory[i], &msg->points[i]);
}

inline void msgMultiDofJointTrajectoryFromEigen(const EigenTrajectoryPointVector& trajectory,
                                                trajectory_msgs::MultiDOFJointTrajectory* msg) {
  msgMultiDofJointTrajectoryFromEigen(trajectory, "base_link", msg);
}

/// A hover point: position and yaw, zero velocity and acceleration.
inline void msgMultiDofJointTrajectoryFromPositionYaw(const Eigen::Vector3d& position, double yaw,
                                                      trajectory_msgs::MultiDOFJointTrajectory* msg) {
  EigenTrajectoryPoint point;
  point.position_W = position;
  point.setFromYaw(yaw);
  msgMultiDofJointTrajectoryFromEigen(point, "base_link", msg);
}

// ---- flat outputs -> full state (differential flatness) --------------------------------------

/// The state of a multirotor (thrust along body z) that flies a flat output's acceleration a, jerk j,
/// snap s (world) with yaw psi, its rate and acceleration (Mellinger 2012, section 2.4), with exact
/// yaw-rate terms for the heading definition x_C = (cos psi, sin psi, 0), y_B = z_B x x_C / |.|:
/// orientation R_WB = [x_B y_B z_B], acceleration_body = R^T (a + g e_z) (what an IMU reads),
/// angular velocity and acceleration in the body frame.
inline void EigenMavStateFromEigenTrajectoryPoint(const Eigen::Vector3d& acceleration, const Eigen::Vector3d& jerk,
                                                  const Eigen::Vector3d& snap, double yaw, double yaw_rate,
                                                  double yaw_acceleration, double magnitude_of_gravity,
                                                  Eigen::Quaterniond* orientation, Eigen::Vector3d* acceleration_body,
                                                  Eigen::Vector3d* angular_velocity_body,
                                                  Eigen::Vector3d* angular_acceleration_body) {
  // c z_B = a + g e_z: c the mass-normalised thrust
  const Eigen::Vector3d thrust_W = acceleration + Eigen::Vector3d(0.0, 0.0, magnitude_of_gravity);
  const double c = thrust_W.norm();
  const Eigen::Vector3d z_B = thrust_W / c;
  const Eigen::Vector3d x_C(std::cos(yaw), std::sin(yaw), 0.0), y_C(-std::sin(yaw), std::cos(yaw), 0.0);
  const Eigen::Vector3d y_B = z_B.cross(x_C).normalized();
  const Eigen::Vector3d x_B = y_B.cross(z_B);
  Eigen::Matrix3d R_WB;
  R_WB << x_B, y_B, z_B;
  *orientation = Eigen::Quaterniond(R_WB);
  *acceleration_body = R_WB.transpose() * thrust_W;
  // j = c' z_B + c dz_B/dt, dz_B/dt = w_y x_B - w_x y_B
  const double c_dot = z_B.dot(jerk);
  const double w_x = -y_B.dot(jerk) / c, w_y = x_B.dot(jerk) / c;
  // y_B . x_C = 0 differentiated: (-w_z x_B + w_x z_B) . x_C + y_B . (psi' y_C) = 0
  const double w_z = (w_x * z_B.dot(x_C) + yaw_rate * y_B.dot(y_C)) / x_B.dot(x_C);
  *angular_velocity_body = Eigen::Vector3d(w_x, w_y, w_z);
  // body axes' rates (world): dx_B = w_z y_B - w_y z_B, dy_B = -w_z x_B + w_x z_B, dz_B = w_y x_B - w_x y_B
  const Eigen::Vector3d dx_B = w_z * y_B - w_y * z_B, dy_B = -w_z * x_B + w_x * z_B, dz_B = w_y * x_B - w_x * y_B;
  // s = c'' z_B + 2 c' dz_B + c (dw_y x_B - dw_x y_B + w_y dx_B - w_x dy_B)
  const Eigen::Vector3d rest = snap - 2.0 * c_dot * dz_B - c * (w_y * dx_B - w_x * dy_B);
  const double dw_x = -y_B.dot(rest) / c, dw_y = x_B.dot(rest) / c;
  // the heading constraint differentiated twice
  const Eigen::Vector3d dx_C = yaw_rate * y_C, ddx_C = yaw_acceleration * y_C - yaw_rate * yaw_rate * x_C;
  const double dw_z =
      (dw_x * z_B.dot(x_C) + (-w_z * dx_B + w_x * dz_B).dot(x_C) + 2.0 * dy_B.dot(dx_C) + y_B.dot(ddx_C)) /
      x_B.dot(x_C);
  *angular_acceleration_body = Eigen::Vector3d(dw_x, dw_y, dw_z);
}

/// The same with mav_msgs' gravity (kGravity, Zurich).
inline void EigenMavStateFromEigenTrajectoryPoint(const Eigen::Vector3d& acceleration, const Eigen::Vector3d& jerk,
                                                  const Eigen::Vector3d& snap, double yaw, double yaw_rate,
                                                  double yaw_acceleration, Eigen::Quaterniond* orientation,
                                                  Eigen::Vector3d* acceleration_body,
                                                  Eigen::Vector3d* angular_velocity_body,
                                                  Eigen::Vector3d* angular_acceleration_body) {
  EigenMavStateFromEigenTrajectoryPoint(acceleration, jerk, snap, yaw, yaw_rate, yaw_acceleration, kGravity,
                                        orientation, acceleration_body, angular_velocity_body,
                                        angular_acceleration_body);
}

/// A trajectory point to the state that flies it: a 4-DOF point (a multirotor) through flatness; a
/// 6-DOF point (fully actuated) keeps its orientation and rates (rotated into the body frame).
inline void EigenMavStateFromEigenTrajectoryPoint(const EigenTrajectoryPoint& point, double magnitude_of_gravity,
                                                  EigenMavState* state) {
  state->position_W = point.position_W;
  state->velocity_W = point.velocity_W;
  if (point.degrees_of_freedom == MavActuation::DOF4) {
    EigenMavStateFromEigenTrajectoryPoint(point.acceleration_W, point.jerk_W, point.snap_W, point.getYaw(),
                                          point.getYawRate(), point.getYawAcc(), magnitude_of_gravity,
                                          &state->orientation_W_B, &state->acceleration_B, &state->angular_velocity_B,
                                          &state->angular_acceleration_B);
    return;
  }
  const Eigen::Matrix3d R_BW = point.orientation_W_B.toRotationMatrix().transpose();
  state->orientation_W_B = point.orientation_W_B;
  state->acceleration_B = R_BW * (point.acceleration_W + Eigen::Vector3d(0.0, 0.0, magnitude_of_gravity));
  state->angular_velocity_B = R_BW * point.angular_velocity_W;
  state->angular_acceleration_B = R_BW * point.angular_acceleration_W;
}

inline void EigenMavStateFromEigenTrajectoryPoint(const EigenTrajectoryPoint& point, EigenMavState* state) {
  EigenMavStateFromEigenTrajectoryPoint(point, kGravity, state);
}

}  // namespace mav_msgs
