// Generic odometry / pose sensor (RotorS' GazeboOdometryPlugin without the engine): Gaussian and
// uniform noise on position, attitude and velocities, and a bitmap outage map.
#pragma once

#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rotors_gazebo_plugins {

struct OdometryNoiseParams {
  Eigen::Vector3d normal_position_m = Eigen::Vector3d::Zero();      ///< sigma (noiseNormalPosition)
  Eigen::Vector3d normal_quaternion_rad = Eigen::Vector3d::Zero();  ///< sigma of the small-angle error
  Eigen::Vector3d normal_linear_velocity_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_angular_velocity_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d uniform_position_m = Eigen::Vector3d::Zero();  ///< symmetric bound (noiseUniformPosition)
  Eigen::Vector3d uniform_quaternion_rad = Eigen::Vector3d::Zero();
  Eigen::Vector3d uniform_linear_velocity_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d uniform_angular_velocity_rad_s = Eigen::Vector3d::Zero();
  std::string Validate() const;
};

struct OdometryMeasurement {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();             ///< sensor position in the parent frame
  Eigen::Quaterniond q_WS = Eigen::Quaterniond::Identity();  ///< sensor attitude
  Eigen::Vector3d v_S = Eigen::Vector3d::Zero();             ///< linear velocity, sensor frame
  Eigen::Vector3d omega_S = Eigen::Vector3d::Zero();         ///< angular velocity, sensor frame
};

class OdometryNoise {
 public:
  OdometryNoise(const OdometryNoiseParams& params, uint64_t seed) : params_(params), rng_(seed) {}
  /// p += n + u;  q = q * dq(theta), theta = n + u (body-frame small rotation);  v, omega += n + u
  OdometryMeasurement Corrupt(const OdometryMeasurement& truth);
  /// Pose covariance diag(sigma_p^2, sigma_q^2) and twist covariance diag(sigma_v^2, sigma_w^2),
  /// row-major 6x6 (uniform noise is not in it, as in RotorS).
  std::vector<double> PoseCovariance() const;
  std::vector<double> TwistCovariance() const;

 private:
  Eigen::Vector3d Draw(const Eigen::Vector3d& sigma, const Eigen::Vector3d& bound);
  OdometryNoiseParams params_;
  std::mt19937_64 rng_;
};

/// Where the sensor works: a grayscale image centred on the world origin, `scale_m` metres per
/// pixel; pixel (col, row) = floor((x, y) / scale) + (width, height) / 2. Dark (gray < 128,
/// so palette images and anti-aliased edges work) = no measurement; outside the image the sensor
/// always works.
class OutageMap {
 public:
  static constexpr unsigned char kDarkThreshold = 128;
  /// Throws std::runtime_error naming the file if it cannot be read.
  OutageMap(const std::string& image_path, double scale_m);
  bool Available(double x_m, double y_m) const;
  int Width() const { return width_; }
  int Height() const { return height_; }

 private:
  std::vector<unsigned char> pixels_;
  int width_ = 0, height_ = 0;
  double scale_m_;
};

}  // namespace rotors_gazebo_plugins
