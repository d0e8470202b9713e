// The core state of MSF's pose filter (reference section 8; book eq. 16), Hamilton quaternions:
//   x = [p_W, v_W, q_WI, b_w, b_a]   (16 values; book eq. 16 lists b_a before b_w, MSF's enum
//                                     order, used here and in state_out, puts b_w first)
//   error state dx = [dp, dv, dtheta, db_w, db_a] (15), with q_true = q_hat (x) dq(dtheta):
//   the attitude error is a small rotation in the IMU (body) frame.
#pragma once

#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace msf_updates {

using Matrix15d = Eigen::Matrix<double, 15, 15>;
using Vector15d = Eigen::Matrix<double, 15, 1>;

/// Offsets of the error-state blocks in Matrix15d / Vector15d.
namespace idx {
constexpr int kP = 0, kV = 3, kTheta = 6, kBw = 9, kBa = 12;
}

/// One IMU sample: body rates and specific force in the IMU frame, as sensor_msgs/Imu carries them.
struct ImuReading {
  double t_s = 0.0;
  Eigen::Vector3d omega_m_I = Eigen::Vector3d::Zero();  ///< [rad/s] measured angular velocity
  Eigen::Vector3d a_m_I = Eigen::Vector3d::Zero();      ///< [m/s^2] measured specific force
};

struct CoreState {
  double t_s = 0.0;
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();             ///< [m] IMU position in world
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();             ///< [m/s] IMU velocity in world
  Eigen::Quaterniond q_WI = Eigen::Quaterniond::Identity();  ///< IMU attitude: v_W = R(q_WI) v_I
  Eigen::Vector3d b_w = Eigen::Vector3d::Zero();             ///< [rad/s] gyroscope bias
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();             ///< [m/s^2] accelerometer bias
  Matrix15d P = Matrix15d::Zero();                           ///< error-state covariance
};

/// Throws std::invalid_argument with `why` (a parameter struct's Validate()) unless it is empty.
inline void ThrowIfInvalid(const std::string& why) {
  if (!why.empty()) throw std::invalid_argument(why);
}

/// Skew-symmetric matrix: Skew(a) b = a x b.
inline Eigen::Matrix3d Skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

/// Exp map of SO(3) as a unit quaternion: rotation by |theta| about theta/|theta|.
inline Eigen::Quaterniond QuaternionExp(const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, theta / angle));
}

/// Log map: the rotation vector of q (shortest way round).
inline Eigen::Vector3d QuaternionLog(Eigen::Quaterniond q) {
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  const double s = q.vec().norm();
  if (s < 1e-12) return 2.0 * q.vec();
  return 2.0 * std::atan2(s, q.w()) * q.vec() / s;
}

}  // namespace msf_updates
