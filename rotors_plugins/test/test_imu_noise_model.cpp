// IMU noise model (book eqs. 12-15): the Allan deviation of a long stationary record recovers the
// configured noise density and bias random walk; turn-on bias and gravity at rest.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "rotors_gazebo_plugins/models/imu_noise_model.h"

using namespace rotors_gazebo_plugins;

namespace {
/// Overlapping Allan variance of rate samples y (period dt) at cluster size m:
/// AVAR = 1 / (2 tau^2 (N - 2m)) sum_k (theta_{k+2m} - 2 theta_{k+m} + theta_k)^2, theta = cumsum(y) dt.
double AllanVariance(const std::vector<double>& theta, double dt, size_t m) {
  const size_t n = theta.size() - 1;
  const double tau = m * dt;
  double sum = 0.0;
  for (size_t k = 0; k + 2 * m <= n; ++k) {
    const double d = theta[k + 2 * m] - 2.0 * theta[k + m] + theta[k];
    sum += d * d;
  }
  return sum / (2.0 * tau * tau * static_cast<double>(n - 2 * m + 1));
}

/// Fits AVAR(tau) = N^2 / tau + K^2 tau / 3 (white noise + random walk) over log-spaced tau,
/// weighting relative errors. Returns (N, K).
Eigen::Vector2d FitNoiseDensityAndRandomWalk(const std::vector<double>& y, double dt) {
  std::vector<double> theta(y.size() + 1, 0.0);
  for (size_t i = 0; i < y.size(); ++i) theta[i + 1] = theta[i] + y[i] * dt;
  std::vector<Eigen::Vector2d> rows;
  std::vector<double> rhs;
  for (double tau = 0.05; tau < y.size() * dt / 20.0; tau *= 1.3) {
    const size_t m = static_cast<size_t>(std::round(tau / dt));
    const double t = m * dt;
    const double avar = AllanVariance(theta, dt, m);
    rows.emplace_back(1.0 / t / avar, t / 3.0 / avar);  // divide by avar: relative residuals
    rhs.push_back(1.0);
  }
  Eigen::MatrixXd A(rows.size(), 2);
  Eigen::VectorXd b(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    A.row(i) = rows[i].transpose();
    b[i] = rhs[i];
  }
  const Eigen::Vector2d x = A.colPivHouseholderQr().solve(b);
  return {std::sqrt(x[0]), std::sqrt(x[1])};
}
}  // namespace

TEST(ImuNoiseModel, AllanVarianceRecoversNoiseDensityAndRandomWalk) {
  ImuNoiseParams p;                            // ADIS16448 densities and random walks
  p.gyroscope_bias_correlation_time_s = 1e12;  // pure random walk (eqs. 14-15)
  p.accelerometer_bias_correlation_time_s = 1e12;
  ImuNoiseModel model(p, 42);
  const double dt = 0.01;    // 100 Hz, as in basic.world
  const size_t n = 4000000;  // 40000 s, about 11 hours
  std::vector<double> gyro(n), accel(n);
  const ImuSample rest{Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.8)};
  for (size_t i = 0; i < n; ++i) {
    const ImuSample m = model.Corrupt(rest, dt);
    gyro[i] = m.angular_velocity_I.x();
    accel[i] = m.linear_acceleration_I.y();
  }
  const Eigen::Vector2d g = FitNoiseDensityAndRandomWalk(gyro, dt);
  const Eigen::Vector2d a = FitNoiseDensityAndRandomWalk(accel, dt);
  EXPECT_NEAR(g[0] / p.gyroscope_noise_density, 1.0, 0.10) << "gyro noise density " << g[0];
  EXPECT_NEAR(g[1] / p.gyroscope_random_walk, 1.0, 0.10) << "gyro random walk " << g[1];
  EXPECT_NEAR(a[0] / p.accelerometer_noise_density, 1.0, 0.10) << "accel noise density " << a[0];
  EXPECT_NEAR(a[1] / p.accelerometer_random_walk, 1.0, 0.10) << "accel random walk " << a[1];
}

TEST(ImuNoiseModel, AtRestReadsGravityPlusTurnOnBias) {
  ImuNoiseParams p;
  p.gyroscope_noise_density = p.accelerometer_noise_density = 0.0;
  p.gyroscope_random_walk = p.accelerometer_random_walk = 0.0;
  ImuNoiseModel model(p, 7);
  const ImuSample m = model.Corrupt({Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.8)}, 0.01);
  EXPECT_TRUE(m.linear_acceleration_I.isApprox(Eigen::Vector3d(0, 0, 9.8) + model.AccelerometerTurnOnBias()));
  EXPECT_TRUE(m.angular_velocity_I.isApprox(model.GyroscopeTurnOnBias()));
  EXPECT_GT(model.AccelerometerTurnOnBias().norm(), 0.0);
  // the turn-on bias is drawn with the configured sigma: over many seeds, its spread matches
  double sum_sq = 0.0;
  const int seeds = 4000;
  for (int s = 0; s < seeds; ++s) sum_sq += ImuNoiseModel(p, s).AccelerometerTurnOnBias().squaredNorm();
  EXPECT_NEAR(std::sqrt(sum_sq / (3.0 * seeds)) / p.accelerometer_turn_on_bias_sigma, 1.0, 0.03);
}

TEST(ImuNoiseModel, NoiseFreeConfigurationIsExact) {
  ImuNoiseParams p;
  p.gyroscope_noise_density = p.gyroscope_random_walk = p.gyroscope_turn_on_bias_sigma = 0.0;
  p.accelerometer_noise_density = p.accelerometer_random_walk = p.accelerometer_turn_on_bias_sigma = 0.0;
  ImuNoiseModel model(p, 1);
  const ImuSample truth{Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(0.5, 0, 9.8)};
  for (int i = 0; i < 1000; ++i) {
    const ImuSample m = model.Corrupt(truth, 0.01);
    ASSERT_EQ(m.angular_velocity_I, truth.angular_velocity_I);
    ASSERT_EQ(m.linear_acceleration_I, truth.linear_acceleration_I);
  }
}

TEST(ImuNoiseModel, SameSeedSameSamples) {
  ImuNoiseModel a(ImuNoiseParams(), 3), b(ImuNoiseParams(), 3);
  const ImuSample rest{Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.8)};
  for (int i = 0; i < 100; ++i) {
    const ImuSample x = a.Corrupt(rest, 0.01), y = b.Corrupt(rest, 0.01);
    ASSERT_EQ(x.angular_velocity_I, y.angular_velocity_I);
  }
}
