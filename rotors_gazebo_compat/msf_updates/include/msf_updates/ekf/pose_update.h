// EKF measurement update with a 6-DoF pose sensor (book eqs. 17-18, with the sensor mounted at
// p_ic, q_ic on the IMU, MSF's pose_sensor in "world sensor" mode):
//   p_m = L (p + C(q) p_ic) + n_p                (17)
//   q_m = q (x) q_ic (x) dq_n                    (18)
// L (the visual scale), p_ic and q_ic are fixed here, as msf_simulator.yaml configures them.
#pragma once

#include <string>

#include "msf_updates/ekf/core_state.h"

namespace msf_updates {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

struct PoseSensorParams {
  Eigen::Vector3d p_ic = Eigen::Vector3d::Zero();            ///< [m] sensor position in the IMU frame
  Eigen::Quaterniond q_ic = Eigen::Quaterniond::Identity();  ///< sensor attitude in the IMU frame
  double scale = 1.0;                                        ///< L (pose_initial_scale, or set by the init services)
  double pose_noise_meas_p = 0.01;  ///< [m] used if pose_use_fixed_covariance (or the message has none)
  double pose_noise_meas_q = 0.01;  ///< [rad]
  bool pose_use_fixed_covariance = false;
  double pose_delay_s = 0.02;                   ///< measurement time = header stamp - pose_delay
  double pose_measurement_minimum_dt_s = 0.05;  ///< later measurements closer than this are dropped
  bool enable_mah_outlier_rejection = false;
  double mah_threshold = 5.0;  ///< on the Mahalanobis distance sqrt(r^T S^-1 r)
  std::string Validate() const;
  /// diag(pose_noise_meas_p^2 x3, pose_noise_meas_q^2 x3)
  Eigen::Matrix<double, 6, 6> FixedCovariance() const;
};

/// A pose measurement of the sensor frame in the world. R: 6x6 covariance of [position, rotation
/// vector in the sensor frame] (the upper-left and lower-right blocks of a ROS pose covariance).
struct PoseMeasurement {
  double t_s = 0.0;
  Eigen::Vector3d p_m_W = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_m_WC = Eigen::Quaterniond::Identity();
  Matrix6d R = Matrix6d::Identity();
};

struct UpdateResult {
  bool applied = false;
  double mahalanobis = 0.0;  ///< sqrt(r^T S^-1 r)
};

class PoseUpdate {
 public:
  explicit PoseUpdate(const PoseSensorParams& params);
  /// Residual r = [p_m - h_p, Log((q q_ic)^-1 q_m)] and Jacobian H = d r / d dx (6x15).
  void Linearize(const CoreState& x, const PoseMeasurement& z, Vector6d* r, Eigen::Matrix<double, 6, 15>* H) const;
  /// Kalman update of x in place (Joseph form, symmetric P). `gate`: apply Mahalanobis rejection
  /// if enabled; a rejected measurement leaves x untouched.
  UpdateResult Apply(CoreState* x, const PoseMeasurement& z, bool gate) const;
  const PoseSensorParams& Params() const { return params_; }
  void SetScale(double scale) { params_.scale = scale; }

 private:
  PoseSensorParams params_;
};

}  // namespace msf_updates
