#include "rotors_gazebo_plugins/models/imu_noise_model.h"

#include <cmath>
#include <sstream>

namespace rotors_gazebo_plugins {

std::string ImuNoiseParams::Validate() const {
  std::ostringstream why;
  const std::pair<const char*, double> non_negative[] = {
      {"gyroscopeNoiseDensity", gyroscope_noise_density},
      {"gyroscopeRandomWalk", gyroscope_random_walk},
      {"gyroscopeTurnOnBiasSigma", gyroscope_turn_on_bias_sigma},
      {"accelerometerNoiseDensity", accelerometer_noise_density},
      {"accelerometerRandomWalk", accelerometer_random_walk},
      {"accelerometerTurnOnBiasSigma", accelerometer_turn_on_bias_sigma}};
  for (const auto& p : non_negative)
    if (!(p.second >= 0.0) || !std::isfinite(p.second)) {
      why << p.first << " = " << p.second << " must be >= 0";
      return why.str();
    }
  if (!(gyroscope_bias_correlation_time_s > 0.0))
    why << "gyroscopeBiasCorrelationTime = " << gyroscope_bias_correlation_time_s << " must be > 0 s";
  else if (!(accelerometer_bias_correlation_time_s > 0.0))
    why << "accelerometerBiasCorrelationTime = " << accelerometer_bias_correlation_time_s << " must be > 0 s";
  return why.str();
}

ImuNoiseModel::ImuNoiseModel(const ImuNoiseParams& params, uint64_t seed) : params_(params), rng_(seed) {
  for (int i = 0; i < 3; ++i)
    gyroscope_turn_on_bias_[i] = params_.gyroscope_turn_on_bias_sigma * standard_normal_(rng_);
  for (int i = 0; i < 3; ++i)
    accelerometer_turn_on_bias_[i] = params_.accelerometer_turn_on_bias_sigma * standard_normal_(rng_);
}

ImuNoiseModel::Discrete::Discrete(const ImuNoiseParams& p, double dt) : dt_s(dt) {
  const double sqrt_dt = std::sqrt(dt);
  // discrete white noise: sigma_d = sigma_c / sqrt(dt)
  sigma_gd = p.gyroscope_noise_density / sqrt_dt;
  sigma_ad = p.accelerometer_noise_density / sqrt_dt;
  auto gauss_markov = [dt](double random_walk, double tau_s, double* phi, double* sigma_bd) {
    *phi = std::exp(-dt / tau_s);
    // -expm1(-2dt/tau) = 1 - exp(-2 dt / tau), computed without cancellation for tau >> dt
    *sigma_bd = std::sqrt(random_walk * random_walk * tau_s / 2.0 * -std::expm1(-2.0 * dt / tau_s));
  };
  gauss_markov(p.gyroscope_random_walk, p.gyroscope_bias_correlation_time_s, &phi_g, &sigma_bgd);
  gauss_markov(p.accelerometer_random_walk, p.accelerometer_bias_correlation_time_s, &phi_a, &sigma_bad);
}

void ImuNoiseModel::PropagateBias(Eigen::Vector3d* bias, double phi, double sigma_bd) {
  for (int i = 0; i < 3; ++i) (*bias)[i] = phi * (*bias)[i] + sigma_bd * standard_normal_(rng_);
}

ImuSample ImuNoiseModel::Corrupt(const ImuSample& truth, double dt_s) {
  ImuSample m = truth;
  if (!(dt_s > 0.0)) return m;
  if (dt_s != discrete_.dt_s) discrete_ = Discrete(params_, dt_s);  // the sensor's period, usually constant
  const Discrete& d = discrete_;
  PropagateBias(&gyroscope_bias_, d.phi_g, d.sigma_bgd);
  PropagateBias(&accelerometer_bias_, d.phi_a, d.sigma_bad);
  for (int i = 0; i < 3; ++i) {
    m.angular_velocity_I[i] += gyroscope_bias_[i] + gyroscope_turn_on_bias_[i] + d.sigma_gd * standard_normal_(rng_);
    m.linear_acceleration_I[i] +=
        accelerometer_bias_[i] + accelerometer_turn_on_bias_[i] + d.sigma_ad * standard_normal_(rng_);
  }
  return m;
}

}  // namespace rotors_gazebo_plugins
