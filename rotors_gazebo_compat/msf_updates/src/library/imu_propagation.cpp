#include "msf_updates/ekf/imu_propagation.h"

#include <cmath>
#include <sstream>

namespace msf_updates {

std::string CoreNoiseParams::Validate() const {
  const std::pair<const char*, double> densities[] = {{"core/core_noise_acc", core_noise_acc},
                                                      {"core/core_noise_accbias", core_noise_accbias},
                                                      {"core/core_noise_gyr", core_noise_gyr},
                                                      {"core/core_noise_gyrbias", core_noise_gyrbias}};
  std::ostringstream why;
  for (const auto& d : densities)
    if (!std::isfinite(d.second) || d.second <= 0.0) {
      why << d.first << " = " << d.second << " must be a positive noise density";
      return why.str();
    }
  if (!std::isfinite(gravity_m_s2) || gravity_m_s2 <= 0.0)
    why << "core/core_gravity = " << gravity_m_s2 << " must be positive (9.81 on Earth)";
  return why.str();
}

ImuPropagation::ImuPropagation(const CoreNoiseParams& params) : params_(params), g_W_(0.0, 0.0, -params.gravity_m_s2) {
  ThrowIfInvalid(params.Validate());
}

CoreState ImuPropagation::Propagate(const CoreState& x0, const ImuReading& u0, const ImuReading& u1) const {
  using namespace idx;
  CoreState x1 = x0;
  x1.t_s = u1.t_s;
  const double dt = u1.t_s - u0.t_s;
  if (!(dt > 0.0)) return x1;

  // bias-corrected mean readings over [t0, t1]
  const Eigen::Vector3d omega_I = 0.5 * (u0.omega_m_I + u1.omega_m_I) - x0.b_w;
  const Eigen::Vector3d a0_I = u0.a_m_I - x0.b_a, a1_I = u1.a_m_I - x0.b_a;
  const Eigen::Vector3d a_I = 0.5 * (a0_I + a1_I);

  // q' = 1/2 q (x) [0, omega]  ->  q1 = q0 (x) Exp(omega dt)
  x1.q_WI = (x0.q_WI * QuaternionExp(omega_I * dt)).normalized();
  const Eigen::Matrix3d R0 = x0.q_WI.toRotationMatrix(), R1 = x1.q_WI.toRotationMatrix();
  // v' = C(q) (a_m - b_a) + g   (trapezoidal in the world frame)
  x1.v_W = x0.v_W + (0.5 * (R0 * a0_I + R1 * a1_I) + g_W_) * dt;
  // p' = v
  x1.p_W = x0.p_W + 0.5 * (x0.v_W + x1.v_W) * dt;

  // error-state dynamics d(dx)/dt = F dx + G n,  n = [n_a, n_w, n_bw, n_ba]
  Matrix15d F = Matrix15d::Zero();
  F.block<3, 3>(kP, kV).setIdentity();
  F.block<3, 3>(kV, kTheta) = -R0 * Skew(a_I);
  F.block<3, 3>(kV, kBa) = -R0;
  F.block<3, 3>(kTheta, kTheta) = -Skew(omega_I);
  F.block<3, 3>(kTheta, kBw) = -Eigen::Matrix3d::Identity();
  if (params_.core_fixed_bias) {
    F.block<3, 3>(kV, kBa).setZero();
    F.block<3, 3>(kTheta, kBw).setZero();
  }
  // Phi = exp(F dt), third order (F is nilpotent apart from the rotation block)
  const Matrix15d Fdt = F * dt, Fdt2 = Fdt * Fdt;
  const Matrix15d Phi = Matrix15d::Identity() + Fdt + Fdt2 / 2.0 + Fdt2 * Fdt / 6.0;

  Eigen::Matrix<double, 15, 12> G = Eigen::Matrix<double, 15, 12>::Zero();
  G.block<3, 3>(kV, 0) = -R0;
  G.block<3, 3>(kTheta, 3) = -Eigen::Matrix3d::Identity();
  if (!params_.core_fixed_bias) {
    G.block<3, 3>(kBw, 6).setIdentity();
    G.block<3, 3>(kBa, 9).setIdentity();
  }
  Eigen::Matrix<double, 12, 1> q_c;
  q_c << Eigen::Vector3d::Constant(params_.core_noise_acc * params_.core_noise_acc),
      Eigen::Vector3d::Constant(params_.core_noise_gyr * params_.core_noise_gyr),
      Eigen::Vector3d::Constant(params_.core_noise_gyrbias * params_.core_noise_gyrbias),
      Eigen::Vector3d::Constant(params_.core_noise_accbias * params_.core_noise_accbias);
  const Matrix15d GQG = G * q_c.asDiagonal() * G.transpose();
  // Q_d = int_0^dt Phi(s) G Q_c G^T Phi(s)^T ds   (trapezoidal)
  const Matrix15d Q_d = 0.5 * dt * (Phi * GQG * Phi.transpose() + GQG);
  x1.P = Phi * x0.P * Phi.transpose() + Q_d;
  x1.P = 0.5 * (x1.P + x1.P.transpose()).eval();
  return x1;
}

}  // namespace msf_updates
