#include "rotors_gazebo_plugins/models/wind_model.h"

#include <cmath>
#include <sstream>

namespace rotors_gazebo_plugins {

std::string WindParams::Validate() const {
  std::ostringstream why;
  if (!(wind_speed_variance >= 0.0)) why << "windSpeedVariance = " << wind_speed_variance << " must be >= 0";
  else if (!(wind_force_variance >= 0.0)) why << "windForceVariance = " << wind_force_variance << " must be >= 0";
  else if (!(wind_gust_force_variance >= 0.0))
    why << "windGustForceVariance = " << wind_gust_force_variance << " must be >= 0";
  else if (!(wind_gust_duration_s >= 0.0)) why << "windGustDuration = " << wind_gust_duration_s << " must be >= 0 s";
  else if (wind_direction.norm() < 1e-9) why << "windDirection must not be zero";
  else if (wind_gust_direction.norm() < 1e-9) why << "windGustDirection must not be zero";
  return why.str();
}

WindModel::WindModel(const WindParams& params, uint64_t seed) : params_(params), rng_(seed) {
  params_.wind_direction.normalize();
  params_.wind_gust_direction.normalize();
}

double WindModel::Draw(double mean, double variance) {
  if (variance <= 0.0) return mean;
  return std::normal_distribution<double>(mean, std::sqrt(variance))(rng_);
}

WindSample WindModel::Sample(double t_s) {
  WindSample s;
  s.velocity_W = Draw(params_.wind_speed_mean_m_s, params_.wind_speed_variance) * params_.wind_direction;
  s.force_W = Draw(params_.wind_force_mean_n, params_.wind_force_variance) * params_.wind_direction;
  if (t_s >= params_.wind_gust_start_s && t_s < params_.wind_gust_start_s + params_.wind_gust_duration_s)
    s.force_W += Draw(params_.wind_gust_force_mean_n, params_.wind_gust_force_variance) * params_.wind_gust_direction;
  return s;
}

}  // namespace rotors_gazebo_plugins
