// EKF time update from IMU samples (book: the dynamic model under eq. 16):
//   p' = v,   v' = C(q) (a_m - b_a - n_a) + g,   q' = 1/2 q (x) [0, omega_m - b_w - n_w],
//   b_a' = n_ba,   b_w' = n_bw
// integrated between two IMU samples with the mean of their readings (trapezoidal rule), and the
// error-state covariance propagated with P <- Phi P Phi^T + Q_d.
#pragma once

#include <string>

#include "msf_updates/ekf/core_state.h"

namespace msf_updates {

/// MSF's core noise parameters (`core/` namespace). Densities of continuous white noise.
struct CoreNoiseParams {
  double core_noise_acc = 0.002;     ///< sigma_a  [m/s^2/sqrt(Hz)]
  double core_noise_accbias = 5e-8;  ///< sigma_ba [m/s^3/sqrt(Hz)]
  double core_noise_gyr = 0.0004;    ///< sigma_w  [rad/s/sqrt(Hz)]
  double core_noise_gyrbias = 3e-6;  ///< sigma_bw [rad/s^2/sqrt(Hz)]
  bool core_fixed_bias = false;      ///< biases are neither propagated nor estimated
  double gravity_m_s2 = 9.81;        ///< |g|; MSF hard-codes 9.81 (ours: core/core_gravity)
  /// Empty when valid, else one line naming the bad value.
  std::string Validate() const;
};

class ImuPropagation {
 public:
  explicit ImuPropagation(const CoreNoiseParams& params);

  /// Propagates x0 (at u0.t_s) to u1.t_s. Returns the state at u1.t_s with its covariance.
  CoreState Propagate(const CoreState& x0, const ImuReading& u0, const ImuReading& u1) const;

  const CoreNoiseParams& Params() const { return params_; }

 private:
  CoreNoiseParams params_;
  Eigen::Vector3d g_W_;  ///< gravity in world, (0, 0, -|g|)
};

}  // namespace msf_updates
