// IMU measurement model (book eqs. 12-15; the Kalibr/ADIS16448 noise model RotorS uses):
//   omega_m = omega + b_omega + n_omega,   a_m = a + b_a + n_a
//   b: first-order Gauss-Markov with correlation time tau (a random walk for tau -> inf)
//   plus a constant turn-on bias drawn once.
#pragma once

#include <random>
#include <string>

#include <Eigen/Core>

#include "rotors_gazebo_plugins/models/standard_normal.h"

namespace rotors_gazebo_plugins {

/// Defaults are the ADIS16448 values of RotorS (reference section 4.4).
struct ImuNoiseParams {
  double gyroscope_noise_density = 2.0 * 35.0 / 3600.0 / 180.0 * M_PI;  ///< [rad/s/sqrt(Hz)]
  double gyroscope_random_walk = 2.0 * 4.0 / 3600.0 / 180.0 * M_PI;     ///< [rad/s^2/sqrt(Hz)]
  double gyroscope_bias_correlation_time_s = 1.0e3;                     ///< [s]
  double gyroscope_turn_on_bias_sigma = 0.5 / 180.0 * M_PI;             ///< [rad/s]
  double accelerometer_noise_density = 2.0 * 2.0e-3;                    ///< [m/s^2/sqrt(Hz)]
  double accelerometer_random_walk = 2.0 * 3.0e-3;                      ///< [m/s^3/sqrt(Hz)]
  double accelerometer_bias_correlation_time_s = 300.0;                 ///< [s]
  double accelerometer_turn_on_bias_sigma = 20.0e-3 * 9.8;              ///< [m/s^2]
  std::string Validate() const;
};

struct ImuSample {
  Eigen::Vector3d angular_velocity_I;     ///< [rad/s]
  Eigen::Vector3d linear_acceleration_I;  ///< [m/s^2] specific force
};

class ImuNoiseModel {
 public:
  /// Draws the turn-on biases from `seed`.
  ImuNoiseModel(const ImuNoiseParams& params, uint64_t seed);

  /// Adds bias and white noise to a true sample taken dt after the previous one.
  ImuSample Corrupt(const ImuSample& truth, double dt_s);

  const Eigen::Vector3d& GyroscopeBias() const { return gyroscope_bias_; }
  const Eigen::Vector3d& AccelerometerBias() const { return accelerometer_bias_; }
  const Eigen::Vector3d& GyroscopeTurnOnBias() const { return gyroscope_turn_on_bias_; }
  const Eigen::Vector3d& AccelerometerTurnOnBias() const { return accelerometer_turn_on_bias_; }
  /// Total bias now (Gauss-Markov + turn-on), what an estimator should recover.
  Eigen::Vector3d TotalGyroscopeBias() const { return gyroscope_bias_ + gyroscope_turn_on_bias_; }
  Eigen::Vector3d TotalAccelerometerBias() const { return accelerometer_bias_ + accelerometer_turn_on_bias_; }

 private:
  /// One axis-triple step of: b_k = exp(-dt/tau) b_{k-1} + sigma_bd N(0,1),
  /// sigma_bd = sqrt(-sigma_b^2 tau / 2 (exp(-2 dt / tau) - 1))   (Kalibr; -> sigma_b sqrt(dt) as tau -> inf)
  void PropagateBias(Eigen::Vector3d* bias, double phi, double sigma_bd);

  /// The discrete-time coefficients for one sample period dt (computed again when dt changes).
  struct Discrete {
    Discrete() = default;
    Discrete(const ImuNoiseParams& p, double dt);
    double dt_s = -1.0;
    double sigma_gd = 0.0, sigma_ad = 0.0;  ///< white noise, discrete: sigma_c / sqrt(dt)
    double phi_g = 1.0, sigma_bgd = 0.0;    ///< gyroscope bias: exp(-dt/tau), sigma_bd
    double phi_a = 1.0, sigma_bad = 0.0;    ///< accelerometer bias
  };

  ImuNoiseParams params_;
  Discrete discrete_;
  std::mt19937_64 rng_;
  StandardNormal standard_normal_{0.0, 1.0};
  Eigen::Vector3d gyroscope_bias_ = Eigen::Vector3d::Zero(), accelerometer_bias_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyroscope_turn_on_bias_, accelerometer_turn_on_bias_;
};

}  // namespace rotors_gazebo_plugins
