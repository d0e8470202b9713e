#include "rotors_gazebo_plugins/models/airspeed_model.h"

#include <cmath>
#include <sstream>

namespace rotors_gazebo_plugins {

std::string AirspeedParams::Validate() const {
  std::ostringstream why;
  if (!(noise_stddev_m_s >= 0.0)) why << "noiseStdDev " << noise_stddev_m_s << " must be >= 0 m/s";
  else if (!pitot_axis_B.allFinite()) why << "pitotAxis must be finite (0 0 0 for a 3-axis sensor)";
  return why.str();
}

AirspeedModel::AirspeedModel(const AirspeedParams& params, uint64_t seed)
    : params_(params),
      a_B_(params.IsPitot() ? params.pitot_axis_B.normalized() : Eigen::Vector3d::Zero()),
      rng_(seed) {}

Eigen::Vector3d AirspeedModel::Measure(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& v_W,
                                       const Eigen::Vector3d& v_wind_W) {
  // eq. (19): v_air = v_wind - v, expressed in the body frame
  const Eigen::Vector3d v_air_B = R_WB.transpose() * (v_wind_W - v_W);
  const double sigma = params_.noise_stddev_m_s;
  if (params_.IsPitot()) {
    // Note 10: a pitot tube senses the inflow along its own axis only
    return (a_B_.dot(v_air_B) + sigma * unit_normal_(rng_)) * a_B_;
  }
  return v_air_B + sigma * Eigen::Vector3d(unit_normal_(rng_), unit_normal_(rng_), unit_normal_(rng_));
}

}  // namespace rotors_gazebo_plugins
