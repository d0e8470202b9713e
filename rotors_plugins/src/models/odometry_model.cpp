#include "rotors_gazebo_plugins/models/odometry_model.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <stb_image.h>

#include "rotors_gazebo_plugins/models/standard_normal.h"

namespace rotors_gazebo_plugins {

std::string OdometryNoiseParams::Validate() const {
  const std::pair<const char*, Eigen::Vector3d> all[] = {
      {"noiseNormalPosition", normal_position_m},
      {"noiseNormalQuaternion", normal_quaternion_rad},
      {"noiseNormalLinearVelocity", normal_linear_velocity_m_s},
      {"noiseNormalAngularVelocity", normal_angular_velocity_rad_s},
      {"noiseUniformPosition", uniform_position_m},
      {"noiseUniformQuaternion", uniform_quaternion_rad},
      {"noiseUniformLinearVelocity", uniform_linear_velocity_m_s},
      {"noiseUniformAngularVelocity", uniform_angular_velocity_rad_s}};
  for (const auto& p : all)
    if (!(p.second.minCoeff() >= 0.0) || !p.second.allFinite()) {
      std::ostringstream why;
      why << p.first << " = [" << p.second.transpose() << "] must be >= 0 in every axis";
      return why.str();
    }
  return {};
}

Eigen::Vector3d OdometryNoise::Draw(const Eigen::Vector3d& sigma, const Eigen::Vector3d& bound) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  StandardNormal normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int i = 0; i < 3; ++i) {
    if (sigma[i] > 0.0) n[i] += sigma[i] * normal(rng_);
    if (bound[i] > 0.0) n[i] += bound[i] * uniform(rng_);
  }
  return n;
}

OdometryMeasurement OdometryNoise::Corrupt(const OdometryMeasurement& truth) {
  OdometryMeasurement m = truth;
  m.p_W += Draw(params_.normal_position_m, params_.uniform_position_m);
  const Eigen::Vector3d theta = Draw(params_.normal_quaternion_rad, params_.uniform_quaternion_rad);
  // q(theta) ~ [1, theta/2], normalised
  m.q_WS = (truth.q_WS * Eigen::Quaterniond(1.0, theta.x() / 2, theta.y() / 2, theta.z() / 2)).normalized();
  m.v_S += Draw(params_.normal_linear_velocity_m_s, params_.uniform_linear_velocity_m_s);
  m.omega_S += Draw(params_.normal_angular_velocity_rad_s, params_.uniform_angular_velocity_rad_s);
  return m;
}

namespace {
std::vector<double> Diagonal6(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  std::vector<double> c(36, 0.0);
  for (int i = 0; i < 3; ++i) {
    c[i * 6 + i] = a[i] * a[i];
    c[(i + 3) * 6 + i + 3] = b[i] * b[i];
  }
  return c;
}
}  // namespace

std::vector<double> OdometryNoise::PoseCovariance() const {
  return Diagonal6(params_.normal_position_m, params_.normal_quaternion_rad);
}

std::vector<double> OdometryNoise::TwistCovariance() const {
  return Diagonal6(params_.normal_linear_velocity_m_s, params_.normal_angular_velocity_rad_s);
}

OutageMap::OutageMap(const std::string& image_path, double scale_m) : scale_m_(scale_m) {
  if (!(scale_m > 0.0)) throw std::runtime_error("covarianceImageScale must be > 0 m/pixel");
  int channels = 0;
  unsigned char* data = stbi_load(image_path.c_str(), &width_, &height_, &channels, 1);
  if (!data) {
    throw std::runtime_error("cannot read outage map image '" + image_path + "': " + stbi_failure_reason());
  }
  pixels_.assign(data, data + static_cast<size_t>(width_) * height_);
  stbi_image_free(data);
}

bool OutageMap::Available(double x_m, double y_m) const {
  const long col = static_cast<long>(std::floor(x_m / scale_m_)) + width_ / 2;
  const long row = static_cast<long>(std::floor(y_m / scale_m_)) + height_ / 2;
  if (col < 0 || row < 0 || col >= width_ || row >= height_) return true;
  return pixels_[static_cast<size_t>(row) * width_ + col] >= kDarkThreshold;
}

}  // namespace rotors_gazebo_plugins
