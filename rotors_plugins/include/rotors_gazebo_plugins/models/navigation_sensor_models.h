// Navigation sensors of RotorS (RotorS' gazebo_gps_plugin.cpp, gazebo_magnetometer_plugin.cpp,
// gazebo_pressure_plugin.cpp), engine-free:
//   GPS:          position in the world (ENU) + N(0, sigma_h/v) -> WGS84 latitude, longitude, altitude
//                 at the world's <spherical_coordinates>; ground speed = v_W + N(0, sigma)
//   GPS, PX4's:   PX4-SITL_gazebo-classic's gazebo_gps_plugin: every physics step dt a bias walks,
//                 b_{k+1} = b_k + sigma_rw sqrt(dt) n_k dt - b_k / tau  (tau counted in steps, as PX4
//                 integrates it), the reading p_W + sigma_p sqrt(dt) n + b joins a delay line, and a
//                 fix publishes the reading of `delay` ago
//   magnetometer: B_B = R_WB^T m_W + b_B + n,  m_W the reference field (NED parameters rotated into
//                 the ENU world: RotorS used N, E, D as x, y, z), b_B drawn once from U(-b, b)
//   barometer:    the 1976 standard atmosphere below 11 km + N(0, sigma^2)
#pragma once

#include <deque>
#include <random>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rotors_gazebo_plugins/models/standard_atmosphere.h"
#include "rotors_gazebo_plugins/models/standard_normal.h"

namespace rotors_gazebo_plugins {

/// Where the world origin is on the Earth and how the world is turned (SDF <spherical_coordinates>).
struct GeodeticOrigin {
  double latitude_deg = 0.0, longitude_deg = 0.0, elevation_m = 0.0, heading_deg = 0.0;
};

/// WGS84 latitude [deg], longitude [deg] and altitude [m] of a point given in the world frame.
Eigen::Vector3d GeodeticFromWorld(const GeodeticOrigin& origin, const Eigen::Vector3d& p_W);

/// gpsNoiseModel: RotorS' white noise on each fix, or PX4's Gazebo GPS (a random-walk bias).
enum class GpsNoiseModel { kWhite, kRandomWalk };

struct GpsParams {
  /// horPosStdDev, verPosStdDev: the accuracy each fix reports (NavSatFix covariance, HIL_GPS eph/epv);
  /// with the white model also the noise it adds
  double hor_pos_std_dev_m = 3.0;
  double ver_pos_std_dev_m = 6.0;
  double hor_vel_std_dev_m_s = 0.1;                   ///< horVelStdDev (white model)
  double ver_vel_std_dev_m_s = 0.1;                   ///< verVelStdDev (white model)
  GpsNoiseModel noise_model = GpsNoiseModel::kWhite;  ///< gpsNoiseModel: "white" or "random_walk"
  // the random-walk model; defaults: PX4-SITL_gazebo-classic's include/gazebo_gps_plugin.h
  double xy_random_walk = 2.0;           ///< gpsXYRandomWalk [(m/s)/sqrt(Hz)]
  double z_random_walk = 4.0;            ///< gpsZRandomWalk [(m/s)/sqrt(Hz)]
  double xy_noise_density = 2e-4;        ///< gpsXYNoiseDensity [m/sqrt(Hz)]
  double z_noise_density = 4e-4;         ///< gpsZNoiseDensity [m/sqrt(Hz)]
  double vxy_noise_density = 0.2;        ///< gpsVXYNoiseDensity [(m/s)/sqrt(Hz)]
  double vz_noise_density = 0.4;         ///< gpsVZNoiseDensity [(m/s)/sqrt(Hz)]
  double correlation_time_steps = 60.0;  ///< gpsCorrelationTime: tau of the bias, in physics steps (as PX4)
  double delay_s = 0.12;                 ///< gpsDelay [s]
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

/// PX4's Gazebo GPS (the random-walk model), stepped with the physics.
class RandomWalkGpsModel {
 public:
  RandomWalkGpsModel(const GpsParams& params, const GeodeticOrigin& origin, uint64_t seed);
  /// One physics step of dt_s ending at t_s: the bias walks and the step's reading joins the delay line.
  void Step(double t_s, double dt_s, const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W);
  /// The fix at t_s: the oldest reading not older than delay_s (false before the first step).
  bool Fix(double t_s, GpsSample* sample);
  const Eigen::Vector3d& Bias() const { return bias_W_m_; }
  const GpsParams& Params() const { return params_; }

 private:
  struct Reading {
    double t_s;
    GpsSample sample;
  };
  GpsParams params_;
  GeodeticOrigin origin_;
  std::mt19937_64 rng_;
  StandardNormal unit_normal_{0.0, 1.0};
  Eigen::Vector3d bias_W_m_ = Eigen::Vector3d::Zero();
  std::deque<Reading> delay_line_;
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
