// Wind of RotorS' wind plugin, with the variances actually used: wind speed (acts on the rotors
// through their airspeed), a constant force and a timed gust force on a link.
#pragma once

#include <random>
#include <string>

#include <Eigen/Core>

namespace rotors_gazebo_plugins {

struct WindParams {
  double wind_speed_mean_m_s = 0.0;  ///< windSpeedMean
  double wind_speed_variance = 0.0;  ///< windSpeedVariance [(m/s)^2]
  Eigen::Vector3d wind_direction = Eigen::Vector3d::UnitX();
  double wind_force_mean_n = 0.0;    ///< windForceMean
  double wind_force_variance = 0.0;  ///< [N^2]
  double wind_gust_start_s = 10.0;
  double wind_gust_duration_s = 0.0;
  double wind_gust_force_mean_n = 0.0;
  double wind_gust_force_variance = 0.0;  ///< [N^2]
  Eigen::Vector3d wind_gust_direction = Eigen::Vector3d::UnitY();
  std::string Validate() const;
};

struct WindSample {
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();  ///< [m/s]
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();     ///< [N], constant wind + gust
};

class WindModel {
 public:
  WindModel(const WindParams& params, uint64_t seed);
  /// Magnitudes are drawn from N(mean, variance) every call (white, seeded).
  WindSample Sample(double sim_time_s);

 private:
  double Draw(double mean, double variance);
  WindParams params_;
  std::mt19937_64 rng_;
};

}  // namespace rotors_gazebo_plugins
