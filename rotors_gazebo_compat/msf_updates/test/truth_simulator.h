// A truth model for the estimator tests: a smooth 3D trajectory with rotation, the IMU of book
// eqs. 12-15 (white noise + random-walk biases with the filter's densities) and the pose sensor
// of eqs. 17-18, all drawn from one seeded generator.
#pragma once

#include <random>

#include "msf_updates/ekf/pose_ekf.h"

namespace msf_updates {

struct TruthSample {
  CoreState x;     ///< true state (P unused)
  ImuReading imu;  ///< noisy IMU at x.t_s
};

class TruthSimulator {
 public:
  TruthSimulator(const CoreNoiseParams& noise, const PoseSensorParams& sensor, const InitialUncertainty& init,
                 uint64_t seed, double motion_scale = 1.0)
      : noise_(noise), sensor_(sensor), rng_(seed), motion_(motion_scale) {
    for (int i = 0; i < 3; ++i) b_w_[i] = init.sigma_b_w_rad_s * n_(rng_);
    for (int i = 0; i < 3; ++i) b_a_[i] = init.sigma_b_a_m_s2 * n_(rng_);
  }

  static constexpr double kImuDt_s = 0.01;
  static constexpr double kSubsteps = 20;

  /// Advances the truth to step k (t = k * kImuDt_s) and returns it with its IMU sample.
  TruthSample Step(int k) {
    const double t = k * kImuDt_s;
    if (k > 0) {
      // attitude: q' = 1/2 q (x) [0, omega_I], fine substeps of the analytic body rate
      const double h = kImuDt_s / kSubsteps;
      for (int i = 0; i < kSubsteps; ++i)
        q_ = (q_ * QuaternionExp(Omega(t - kImuDt_s + (i + 0.5) * h) * h)).normalized();
      // biases: random walks (eqs. 14-15), discretised
      for (int i = 0; i < 3; ++i) b_w_[i] += noise_.core_noise_gyrbias * std::sqrt(kImuDt_s) * n_(rng_);
      for (int i = 0; i < 3; ++i) b_a_[i] += noise_.core_noise_accbias * std::sqrt(kImuDt_s) * n_(rng_);
    }
    TruthSample s;
    s.x.t_s = t;
    s.x.p_W = Position(t);
    s.x.v_W = Velocity(t);
    s.x.q_WI = q_;
    s.x.b_w = b_w_;
    s.x.b_a = b_a_;
    const Eigen::Vector3d g_W(0.0, 0.0, -noise_.gravity_m_s2);
    s.imu.t_s = t;
    const double sigma_w = noise_.core_noise_gyr / std::sqrt(kImuDt_s),
                 sigma_a = noise_.core_noise_acc / std::sqrt(kImuDt_s);
    // (12)-(13): omega_m = omega + b_w + n_w,  a_m = C^T (a - g) + b_a + n_a
    s.imu.omega_m_I = Omega(t) + b_w_ + sigma_w * Normal3();
    s.imu.a_m_I = q_.conjugate() * (Acceleration(t) - g_W) + b_a_ + sigma_a * Normal3();
    return s;
  }

  /// The pose sensor's measurement of the true state (17)-(18), covariance diag(sigma_p^2, sigma_q^2).
  PoseMeasurement Measure(const CoreState& x) {
    PoseMeasurement z;
    z.t_s = x.t_s;
    const double sp = sensor_.pose_noise_meas_p, sq = sensor_.pose_noise_meas_q;
    z.p_m_W = sensor_.scale * (x.p_W + x.q_WI * sensor_.p_ic) + sp * Normal3();
    z.q_m_WC = x.q_WI * sensor_.q_ic * QuaternionExp(sq * Normal3());
    z.R.setZero();
    z.R.diagonal() << Eigen::Vector3d::Constant(sp * sp), Eigen::Vector3d::Constant(sq * sq);
    return z;
  }

  // Trajectory: at rest at t = 0, then a figure in x-y, heave in z, yawing and rolling.
  Eigen::Vector3d Position(double t) const {
    return motion_ *
           Eigen::Vector3d(1.0 - std::cos(0.5 * t), 0.5 * (1.0 - std::cos(0.8 * t)), 0.3 * (1.0 - std::cos(0.6 * t)));
  }
  Eigen::Vector3d Velocity(double t) const {
    return motion_ * Eigen::Vector3d(0.5 * std::sin(0.5 * t), 0.4 * std::sin(0.8 * t), 0.18 * std::sin(0.6 * t));
  }
  Eigen::Vector3d Acceleration(double t) const {
    return motion_ * Eigen::Vector3d(0.25 * std::cos(0.5 * t), 0.32 * std::cos(0.8 * t), 0.108 * std::cos(0.6 * t));
  }
  Eigen::Vector3d Omega(double t) const {
    return motion_ * Eigen::Vector3d(0.3 * std::sin(0.7 * t), 0.2 * std::sin(0.9 * t), 0.4 * std::sin(0.3 * t));
  }

 private:
  Eigen::Vector3d Normal3() { return Eigen::Vector3d(n_(rng_), n_(rng_), n_(rng_)); }
  CoreNoiseParams noise_;
  PoseSensorParams sensor_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> n_{0.0, 1.0};
  double motion_;
  Eigen::Quaterniond q_ = Eigen::Quaterniond::Identity();
  Eigen::Vector3d b_w_, b_a_;
};

/// Error state of an estimate against the truth: [dp, dv, dtheta (body), db_w, db_a].
inline Vector15d ErrorState(const CoreState& truth, const CoreState& estimate) {
  Vector15d e;
  e.segment<3>(idx::kP) = truth.p_W - estimate.p_W;
  e.segment<3>(idx::kV) = truth.v_W - estimate.v_W;
  e.segment<3>(idx::kTheta) = QuaternionLog(estimate.q_WI.conjugate() * truth.q_WI);
  e.segment<3>(idx::kBw) = truth.b_w - estimate.b_w;
  e.segment<3>(idx::kBa) = truth.b_a - estimate.b_a;
  return e;
}

/// Chi-square quantile (Wilson-Hilferty; accurate to < 1 % for k >= 10).
inline double ChiSquareQuantile(double k, double z_normal) {
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z_normal * std::sqrt(a), 3);
}

}  // namespace msf_updates
