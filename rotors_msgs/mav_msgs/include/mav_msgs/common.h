// Eigen helpers of the mav_comm API (mav_comm's mav_msgs/include/mav_msgs/common.h): message <-> Eigen, skew/vee,
// rotation vectors, yaw and Euler angles, gravity by latitude and height, rotor speeds from an
// allocation matrix. Header-only.
#pragma once

#include <cmath>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <geometry_msgs/Point.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Vector3.h>

namespace mav_msgs {

/// Norms below this count as zero (quaternions, rotation vectors).
constexpr double kSmallValueCheck = 1.e-6;
constexpr double kNumNanosecondsPerSecond = 1.e9;

inline Eigen::Vector3d vector3FromMsg(const geometry_msgs::Vector3& msg) { return {msg.x, msg.y, msg.z}; }

inline Eigen::Vector3d vector3FromPointMsg(const geometry_msgs::Point& msg) { return {msg.x, msg.y, msg.z}; }

/// Normalised; a quaternion of (almost) zero norm gives the identity.
inline Eigen::Quaterniond quaternionFromMsg(const geometry_msgs::Quaternion& msg) {
  Eigen::Quaterniond q(msg.w, msg.x, msg.y, msg.z);
  if (!(q.norm() >= kSmallValueCheck)) return Eigen::Quaterniond::Identity();
  return q.normalized();
}

inline void vectorEigenToMsg(const Eigen::Vector3d& v, geometry_msgs::Vector3* msg) {
  msg->x = v.x();
  msg->y = v.y();
  msg->z = v.z();
}

inline void pointEigenToMsg(const Eigen::Vector3d& p, geometry_msgs::Point* msg) {
  msg->x = p.x();
  msg->y = p.y();
  msg->z = p.z();
}

inline void quaternionEigenToMsg(const Eigen::Quaterniond& q, geometry_msgs::Quaternion* msg) {
  msg->w = q.w();
  msg->x = q.x();
  msg->y = q.y();
  msg->z = q.z();
}

/// [v]x, with [v]x u = v x u.
inline Eigen::Matrix3d skewMatrixFromVector(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return S;
}

/// The vee map, inverse of skewMatrixFromVector.
inline Eigen::Vector3d vectorFromSkewMatrix(const Eigen::Matrix3d& S) { return {S(2, 1), S(0, 2), S(1, 0)}; }

/// R^T R = I and det R = +1, within 1e-6.
inline bool isRotationMatrix(const Eigen::Matrix3d& R) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < kSmallValueCheck &&
         std::abs(R.determinant() - 1.0) < kSmallValueCheck;
}

/// Rodrigues: exp([v]x), the rotation by |v| about v / |v|.
inline void matrixFromRotationVector(const Eigen::Vector3d& v, Eigen::Matrix3d* R) {
  const double angle = v.norm();
  if (angle < kSmallValueCheck) {
    *R = Eigen::Matrix3d::Identity() + skewMatrixFromVector(v);
    return;
  }
  *R = Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

/// log(R) as a rotation vector (angle in [0, pi]).
inline void vectorFromRotationMatrix(const Eigen::Matrix3d& R, Eigen::Vector3d* v) {
  const Eigen::AngleAxisd aa(R);
  *v = aa.angle() * aa.axis();
}

/// psi = atan2(2 (w z + x y), 1 - 2 (y^2 + z^2)) (z-y'-x'' convention).
inline double yawFromQuaternion(const Eigen::Quaterniond& q) {
  return std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()), 1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
}

inline Eigen::Quaterniond quaternionFromYaw(double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
}

/// Replaces the yaw of *q, keeping roll and pitch.
inline void setQuaternionYaw(double yaw, Eigen::Quaterniond* q) {
  // Rz(yaw) Ry(pitch) Rx(roll) = Rz(yaw - yaw_now) q
  const double yaw_now = yawFromQuaternion(*q);
  *q = (quaternionFromYaw(yaw - yaw_now) * (*q)).normalized();
}

/// (roll, pitch, yaw) of the z-y'-x'' convention: R = Rz(yaw) Ry(pitch) Rx(roll).
inline void getEulerAnglesFromQuaternion(const Eigen::Quaternion<double>& q, Eigen::Vector3d* euler_angles) {
  const double w = q.w(), x = q.x(), y = q.y(), z = q.z();
  const double roll = std::atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y));
  const double sin_pitch = std::max(-1.0, std::min(1.0, 2.0 * (w * y - z * x)));
  *euler_angles = {roll, std::asin(sin_pitch), yawFromQuaternion(q)};
}

/// The yaw-only orientation quaternion into a message.
inline void setQuaternionMsgFromYaw(double yaw, geometry_msgs::Quaternion* msg) {
  quaternionEigenToMsg(quaternionFromYaw(yaw), msg);
}

/// The angular velocity (0, 0, yaw_rate) into a message.
inline void setAngularVelocityMsgFromYawRate(double yaw_rate, geometry_msgs::Vector3* msg) {
  vectorEigenToMsg(Eigen::Vector3d(0.0, 0.0, yaw_rate), msg);
}

namespace internal {
/// Coefficients of the left Jacobian of SO(3), J(phi) = I + a [phi]x + b [phi]x^2, and their
/// derivatives by theta = |phi|: a = (1 - cos t) / t^2, b = (t - sin t) / t^3 (series near 0).
struct LeftJacobianCoefficients {
  double a, b, da_dtheta, db_dtheta;
  explicit LeftJacobianCoefficients(double t) {
    if (t < 1e-4) {
      a = 0.5 - t * t / 24.0;
      b = 1.0 / 6.0 - t * t / 120.0;
      da_dtheta = -t / 12.0;
      db_dtheta = -t / 60.0;
      return;
    }
    const double s = std::sin(t), c = std::cos(t);
    a = (1.0 - c) / (t * t);
    b = (t - s) / (t * t * t);
    da_dtheta = (t * s - 2.0 * (1.0 - c)) / (t * t * t);
    db_dtheta = (3.0 * s - 2.0 * t - t * c) / (t * t * t * t);
  }
};
}  // namespace internal

/// Angular velocity (world frame) of R = exp([phi]x) from the rotation vector's rate:
/// omega = J(phi) dphi/dt, J the left Jacobian of SO(3) (Peres, "Finite rotations and angular velocity").
inline Eigen::Vector3d omegaFromRotationVector(const Eigen::Vector3d& rot_vec, const Eigen::Vector3d& rot_vec_vel) {
  const internal::LeftJacobianCoefficients k(rot_vec.norm());
  const Eigen::Matrix3d Phi = skewMatrixFromVector(rot_vec);
  // omega = (I + a [phi]x + b [phi]x^2) dphi/dt
  return rot_vec_vel + k.a * Phi * rot_vec_vel + k.b * Phi * Phi * rot_vec_vel;
}

/// Angular acceleration (world frame): d/dt (J(phi) dphi/dt) = dJ/dt dphi/dt + J(phi) d2phi/dt2.
inline Eigen::Vector3d omegaDotFromRotationVector(const Eigen::Vector3d& rot_vec, const Eigen::Vector3d& rot_vec_vel,
                                                  const Eigen::Vector3d& rot_vec_acc) {
  const double theta = rot_vec.norm();
  const internal::LeftJacobianCoefficients k(theta);
  const double theta_dot = theta > 0.0 ? rot_vec.dot(rot_vec_vel) / theta : 0.0;
  const Eigen::Matrix3d Phi = skewMatrixFromVector(rot_vec), Phi_dot = skewMatrixFromVector(rot_vec_vel);
  // dJ/dt = a' theta' [phi]x + a [phi']x + b' theta' [phi]x^2 + b ([phi']x [phi]x + [phi]x [phi']x)
  const Eigen::Matrix3d J_dot = k.da_dtheta * theta_dot * Phi + k.a * Phi_dot + k.db_dtheta * theta_dot * Phi * Phi +
                                k.b * (Phi_dot * Phi + Phi * Phi_dot);
  return J_dot * rot_vec_vel + omegaFromRotationVector(rot_vec, rot_vec_acc);
}

inline double nanosecondsToSeconds(int64_t nanoseconds) {
  return static_cast<double>(nanoseconds) / kNumNanosecondsPerSecond;
}

/// Truncated towards zero, as a cast.
inline int64_t secondsToNanoseconds(double seconds) { return static_cast<int64_t>(seconds * kNumNanosecondsPerSecond); }

/// Normal gravity [m/s^2] at a height [m] and latitude [rad]:
/// g = 9.780327 ((1 + 0.0053024 sin^2 phi - 0.0000058 sin^2 2 phi) - 3.155e-7 h)
inline double MagnitudeOfGravity(const double height, const double latitude_radians) {
  const double s = std::sin(latitude_radians), s2 = std::sin(2.0 * latitude_radians);
  return 9.780327 * ((1.0 + 0.0053024 * s * s - 0.0000058 * s2 * s2) - 3.155e-7 * height);
}

/// Squared rotor speeds that give the body torque J dw/dt + w x J w and the thrust m |a|,
/// through allocation_inverse (N x 4), the pseudo-inverse of the allocation matrix that maps squared
/// rotor speeds to (roll, pitch, yaw torque, thrust).
inline void getSquaredRotorSpeedsFromAllocationAndState(const Eigen::MatrixXd& allocation_inverse,
                                                        const Eigen::Vector3d& inertia_diagonal, double mass,
                                                        const Eigen::Vector3d& angular_velocity_B,
                                                        const Eigen::Vector3d& angular_acceleration_B,
                                                        const Eigen::Vector3d& thrust_acceleration_B,
                                                        Eigen::VectorXd* rotor_rates_squared) {
  const Eigen::Vector3d J = inertia_diagonal;
  // tau = J dw/dt + w x (J w)
  const Eigen::Vector3d torque =
      J.asDiagonal() * angular_acceleration_B + angular_velocity_B.cross(J.asDiagonal() * angular_velocity_B);
  Eigen::Vector4d wrench;
  wrench << torque, mass * thrust_acceleration_B.norm();
  *rotor_rates_squared = allocation_inverse * wrench;
}

}  // namespace mav_msgs
