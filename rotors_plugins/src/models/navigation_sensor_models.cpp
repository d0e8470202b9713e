#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"

#include <cmath>
#include <sstream>

#include <ignition/math/SphericalCoordinates.hh>

namespace rotors_gazebo_plugins {

namespace {
std::string CheckNonNegative(std::initializer_list<std::pair<const char*, double>> values) {
  for (const auto& [name, value] : values)
    if (!(value >= 0.0) || !std::isfinite(value)) {
      std::ostringstream why;
      why << name << " = " << value << " must be a finite number >= 0";
      return why.str();
    }
  return {};
}
}  // namespace

Eigen::Vector3d GeodeticFromWorld(const GeodeticOrigin& origin, const Eigen::Vector3d& p_W) {
  using ignition::math::Angle;
  const ignition::math::SphericalCoordinates earth(
      ignition::math::SphericalCoordinates::EARTH_WGS84, Angle(origin.latitude_deg * M_PI / 180.0),
      Angle(origin.longitude_deg * M_PI / 180.0), origin.elevation_m, Angle(origin.heading_deg * M_PI / 180.0));
  // LOCAL2: the world frame with the heading applied correctly (ignition-math 6's LOCAL is not).
  const ignition::math::Vector3d lla_rad =
      earth.PositionTransform({p_W.x(), p_W.y(), p_W.z()}, ignition::math::SphericalCoordinates::LOCAL2,
                              ignition::math::SphericalCoordinates::SPHERICAL);
  return {lla_rad.X() * 180.0 / M_PI, lla_rad.Y() * 180.0 / M_PI, lla_rad.Z()};
}

std::string GpsParams::Validate() const {
  if (!(correlation_time_steps >= 1.0) || !std::isfinite(correlation_time_steps))
    return "gpsCorrelationTime = " + std::to_string(correlation_time_steps) +
           " must be >= 1 (physics steps, as PX4's plugin counts it)";
  return CheckNonNegative({{"horPosStdDev", hor_pos_std_dev_m},
                           {"verPosStdDev", ver_pos_std_dev_m},
                           {"horVelStdDev", hor_vel_std_dev_m_s},
                           {"verVelStdDev", ver_vel_std_dev_m_s},
                           {"gpsXYRandomWalk", xy_random_walk},
                           {"gpsZRandomWalk", z_random_walk},
                           {"gpsXYNoiseDensity", xy_noise_density},
                           {"gpsZNoiseDensity", z_noise_density},
                           {"gpsVXYNoiseDensity", vxy_noise_density},
                           {"gpsVZNoiseDensity", vz_noise_density},
                           {"gpsDelay", delay_s}});
}

GpsModel::GpsModel(const GpsParams& params, const GeodeticOrigin& origin, uint64_t seed)
    : params_(params), origin_(origin), rng_(seed) {}

GpsSample GpsModel::Measure(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W) {
  const Eigen::Vector3d sigma_p(params_.hor_pos_std_dev_m, params_.hor_pos_std_dev_m, params_.ver_pos_std_dev_m);
  const Eigen::Vector3d sigma_v(params_.hor_vel_std_dev_m_s, params_.hor_vel_std_dev_m_s, params_.ver_vel_std_dev_m_s);
  Eigen::Vector3d n_p, n_v;
  for (int i = 0; i < 3; ++i) n_p[i] = sigma_p[i] * unit_normal_(rng_);
  for (int i = 0; i < 3; ++i) n_v[i] = sigma_v[i] * unit_normal_(rng_);
  return {GeodeticFromWorld(origin_, p_W + n_p), v_W + n_v};
}

RandomWalkGpsModel::RandomWalkGpsModel(const GpsParams& params, const GeodeticOrigin& origin, uint64_t seed)
    : params_(params), origin_(origin), rng_(seed) {}

void RandomWalkGpsModel::Step(double t_s, double dt_s, const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W) {
  const double root_dt = std::sqrt(dt_s);
  const Eigen::Vector3d sigma_p(params_.xy_noise_density, params_.xy_noise_density, params_.z_noise_density);
  const Eigen::Vector3d sigma_v(params_.vxy_noise_density, params_.vxy_noise_density, params_.vz_noise_density);
  const Eigen::Vector3d sigma_rw(params_.xy_random_walk, params_.xy_random_walk, params_.z_random_walk);
  Eigen::Vector3d n_p, n_v, n_rw;
  for (int i = 0; i < 3; ++i) n_p[i] = sigma_p[i] * root_dt * unit_normal_(rng_);
  for (int i = 0; i < 3; ++i) n_v[i] = sigma_v[i] * root_dt * unit_normal_(rng_);
  for (int i = 0; i < 3; ++i) n_rw[i] = sigma_rw[i] * root_dt * unit_normal_(rng_);
  // b_{k+1} = b_k + sigma_rw sqrt(dt) n_k dt - b_k / tau
  bias_W_m_ += n_rw * dt_s - bias_W_m_ / params_.correlation_time_steps;
  delay_line_.push_back({t_s, {GeodeticFromWorld(origin_, p_W + n_p + bias_W_m_), v_W + n_v}});
}

bool RandomWalkGpsModel::Fix(double t_s, GpsSample* sample) {
  // drop the readings older than the delay, keeping the last one
  while (delay_line_.size() > 1 && t_s - delay_line_.front().t_s > params_.delay_s + 1e-9) delay_line_.pop_front();
  if (delay_line_.empty()) return false;
  *sample = delay_line_.front().sample;
  return true;
}

std::string MagnetometerParams::Validate() const {
  if (!reference_NED_T.allFinite() || reference_NED_T.norm() == 0.0)
    return "refMagNorth/East/Down must be finite and not all zero";
  for (int i = 0; i < 3; ++i) {
    const std::string why = CheckNonNegative(
        {{"noiseNormal", noise_normal_T[i]}, {"noiseUniformInitialBias", noise_uniform_initial_bias_T[i]}});
    if (!why.empty()) return why;
  }
  return {};
}

MagnetometerModel::MagnetometerModel(const MagnetometerParams& params, uint64_t seed) : params_(params), rng_(seed) {
  for (int i = 0; i < 3; ++i) {
    const double b = params_.noise_uniform_initial_bias_T[i];
    bias_B_T_[i] = std::uniform_real_distribution<double>(-b, b)(rng_);
  }
}

Eigen::Vector3d MagnetometerModel::Measure(const Eigen::Quaterniond& q_WB) {
  Eigen::Vector3d n;
  for (int i = 0; i < 3; ++i) n[i] = params_.noise_normal_T[i] * unit_normal_(rng_);
  // B_B = R_WB^T m_W + b_B + n
  return q_WB.conjugate() * params_.ReferenceWorld() + bias_B_T_ + n;
}

std::string PressureParams::Validate() const {
  if (!std::isfinite(reference_altitude_m)) return "referenceAltitude must be finite";
  return CheckNonNegative({{"pressureVariance", pressure_variance_pa2}});
}

PressureModel::PressureModel(const PressureParams& params, uint64_t seed) : params_(params), rng_(seed) {}

double PressureModel::Measure(double z_W_m) {
  return StandardAtmospherePressure(params_.reference_altitude_m + z_W_m) +
         std::sqrt(params_.pressure_variance_pa2) * unit_normal_(rng_);
}

}  // namespace rotors_gazebo_plugins
