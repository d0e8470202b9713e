// The book's airspeed (wind) sensor, section 4, eq. (19) and Note 10. Engine-free.
//   3-axis: v_air_B = R_WB^T (v_wind_W - v_W) + n,  n ~ N(0, sigma^2 I)        (eq. 19 in the body frame)
//   pitot:  v_air_B = (a_B . R_WB^T (v_wind_W - v_W) + n) a_B                   (Note 10: one body axis a_B)
#pragma once

#include <random>
#include <string>

#include <Eigen/Core>

namespace rotors_gazebo_plugins {

struct AirspeedParams {
  double noise_stddev_m_s = 0.0;                           ///< noiseStdDev [m/s] per measured axis
  Eigen::Vector3d pitot_axis_B = Eigen::Vector3d::Zero();  ///< pitotAxis; zero: all three axes
  std::string Validate() const;
  bool IsPitot() const { return pitot_axis_B.squaredNorm() > 0.0; }
};

class AirspeedModel {
 public:
  AirspeedModel(const AirspeedParams& params, uint64_t seed);
  /// v_air in the body frame [m/s] from the attitude R_WB, the body's velocity v_W and the wind v_wind_W.
  Eigen::Vector3d Measure(const Eigen::Matrix3d& R_WB, const Eigen::Vector3d& v_W, const Eigen::Vector3d& v_wind_W);

 private:
  AirspeedParams params_;
  Eigen::Vector3d a_B_;  ///< the unit pitot axis
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
};

}  // namespace rotors_gazebo_plugins
