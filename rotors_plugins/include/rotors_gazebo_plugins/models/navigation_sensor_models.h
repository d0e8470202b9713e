// Navigation sensors of RotorS (rotors_reference.md 4.9-4.11), engine-free:
//   GPS:          position in the world (ENU) + N(0, sigma_h/v) -> WGS84 latitude, longitude, altitude
//                 at the world's <spherical_coordinates>; ground speed = v_W + N(0, sigma)
//   magnetometer: B_B = R_WB^T m_W + b_B + n,  m_W the reference field (NED parameters rotated into
//                 the ENU world: RotorS used N, E, D as x, y, z), b_B drawn once from U(-b, b)
//   barometer:    the 1976 standard atmosphere below 11 km + N(0, sigma^2)
#pragma once

#include <random>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_gazebo_plugins/models/standard_normal.h"

namespace rotors_gazebo_plugins {

/// Where the world origin is on the Earth and how the world is turned (SDF <spherical_coordinates>).
struct GeodeticOrigin {
  double latitude_deg = 0.0, longitude_deg = 0.0, elevation_m = 0.0, heading_deg = 0.0;
};

/// WGS84 latitude [deg], longitude [deg] and altitude [m] of a point given in the world frame.
Eigen::Vector3d GeodeticFromWorld(const GeodeticOrigin& origin, const Eigen::Vector3d& p_W);

struct GpsParams {
  double hor_pos_std_dev_m = 3.0;    ///< horPosStdDev
  double ver_pos_std_dev_m = 6.0;    ///< verPosStdDev
  double hor_vel_std_dev_m_s = 0.1;  ///< horVelStdDev
  double ver_vel_std_dev_m_s = 0.1;  ///< verVelStdDev
  std::string Validate() const;
};

struct GpsSample {
  Eigen::Vector3d latitude_longitude_altitude;  ///< [deg, deg, m]
  Eigen::Vector3d ground_speed_W;               ///< [m/s] world frame
};

class GpsModel {
 public:
  GpsModel(const GpsParams& params, const GeodeticOrigin& origin, uint64_t seed);
  GpsSample Measure(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W);
  const GpsParams& Params() const { return params_; }

 private:
  GpsParams params_;
  GeodeticOrigin origin_;
  std::mt19937_64 rng_;
  StandardNormal unit_normal_{0.0, 1.0};
};

struct MagnetometerParams {
  Eigen::Vector3d reference_NED_T{2.1493e-5, 8.15e-7, 4.2795e-5};          ///< refMagNorth, refMagEast, refMagDown [T]
  Eigen::Vector3d noise_normal_T = Eigen::Vector3d::Zero();                ///< noiseNormal: sigma per axis [T]
  Eigen::Vector3d noise_uniform_initial_bias_T = Eigen::Vector3d::Zero();  ///< noiseUniformInitialBias [T]
  std::string Validate() const;
  /// The reference field in the ENU world frame: (east, north, -down).
  Eigen::Vector3d ReferenceWorld() const { return {reference_NED_T.y(), reference_NED_T.x(), -reference_NED_T.z()}; }
};

class MagnetometerModel {
 public:
  /// Draws the bias from `seed`.
  MagnetometerModel(const MagnetometerParams& params, uint64_t seed);
  /// B_B = R_WB^T m_W + b_B + n  [T]
  Eigen::Vector3d Measure(const Eigen::Quaterniond& q_WB);
  const Eigen::Vector3d& Bias() const { return bias_B_T_; }

 private:
  MagnetometerParams params_;
  std::mt19937_64 rng_;
  Eigen::Vector3d bias_B_T_;
  StandardNormal unit_normal_{0.0, 1.0};
};

struct PressureParams {
  double reference_altitude_m = 500.0;  ///< referenceAltitude: altitude of the world origin
  double pressure_variance_pa2 = 0.0;   ///< pressureVariance [Pa^2]
  std::string Validate() const;
};

/// Standard-atmosphere pressure [Pa] at a geometric altitude [m] (troposphere):
/// h_gp = R_e h / (R_e + h), T = T_0 - L h_gp, p = p_0 (T / T_0)^(g_0 M / (R L)).
double StandardAtmospherePressure(double altitude_m);

class PressureModel {
 public:
  PressureModel(const PressureParams& params, uint64_t seed);
  /// [Pa] at height z_W above the world origin.
  double Measure(double z_W_m);

 private:
  PressureParams params_;
  std::mt19937_64 rng_;
  StandardNormal unit_normal_{0.0, 1.0};
};

}  // namespace rotors_gazebo_plugins
