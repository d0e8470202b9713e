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

void ImuNoiseModel::PropagateBias(Eigen::Vector3d* bias, double random_walk, double tau_s, double dt_s) {
  const double phi = std::exp(-dt_s / tau_s);
  // -expm1(-2dt/tau) = 1 - exp(-2 dt / tau), computed without cancellation for tau >> dt
  const double sigma_bd = std::sqrt(random_walk * random_walk * tau_s / 2.0 * -std::expm1(-2.0 * dt_s / tau_s));
  for (int i = 0; i < 3; ++i) (*bias)[i] = phi * (*bias)[i] + sigma_bd * standard_normal_(rng_);
}

ImuSample ImuNoiseModel::Corrupt(const ImuSample& truth, double dt_s) {
  ImuSample m = truth;
  if (!(dt_s > 0.0)) return m;
  const double sqrt_dt = std::sqrt(dt_s);
  // discrete white noise: sigma_d = sigma_c / sqrt(dt)
  const double sigma_gd = params_.gyroscope_noise_density / sqrt_dt;
  const double sigma_ad = params_.accelerometer_noise_density / sqrt_dt;
  PropagateBias(&gyroscope_bias_, params_.gyroscope_random_walk, params_.gyroscope_bias_correlation_time_s, dt_s);
  PropagateBias(&accelerometer_bias_, params_.accelerometer_random_walk, params_.accelerometer_bias_correlation_time_s,
                dt_s);
  for (int i = 0; i < 3; ++i) {
    m.angular_velocity_I[i] += gyroscope_bias_[i] + gyroscope_turn_on_bias_[i] + sigma_gd * standard_normal_(rng_);
    m.linear_acceleration_I[i] +=
        accelerometer_bias_[i] + accelerometer_turn_on_bias_[i] + sigma_ad * standard_normal_(rng_);
  }
  return m;
}

}  // namespace rotors_gazebo_plugins
