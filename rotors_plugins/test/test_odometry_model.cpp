// Odometry noise statistics and the outage map (white = works, black = no measurement).
#include <gtest/gtest.h>

#include <cmath>

#include "rotors_gazebo_plugins/models/odometry_model.h"

using namespace rotors_gazebo_plugins;

TEST(OutageMap, ShippedMapHasBlackAndWhiteRegionsAndIsCentredOnTheOrigin) {
  OutageMap map(RESOURCE_DIR "/example_odometry_plugin_map1.bmp", 0.1);
  EXPECT_EQ(map.Width(), 640);
  EXPECT_EQ(map.Height(), 400);
  int blocked = 0, total = 0;
  for (double x = -31.95; x < 32.0; x += 0.1)
    for (double y = -19.95; y < 20.0; y += 0.1, ++total) blocked += map.Available(x, y) ? 0 : 1;
  // the black blobs cover about 40 % of the shipped map
  EXPECT_NEAR(static_cast<double>(blocked) / total, 0.40, 0.03) << blocked << " of " << total;
  EXPECT_FALSE(map.Available(16.05, -4.95));  // inside the black blob right of the centre
  EXPECT_TRUE(map.Available(0.05, 0.05));     // the white middle
  EXPECT_TRUE(map.Available(1000.0, 0.0));    // outside the image: always available
  EXPECT_TRUE(map.Available(0.0, -1000.0));
}

TEST(OutageMap, MissingImageIsAClearError) {
  try {
    OutageMap map("/nonexistent/map.bmp", 0.1);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/map.bmp"), std::string::npos);
  }
}

TEST(OdometryNoise, GaussianNoiseHasTheConfiguredSigmaAndCovariance) {
  OdometryNoiseParams p;
  p.normal_position_m = {0.01, 0.02, 0.03};
  p.normal_quaternion_rad = {0.017, 0.017, 0.017};
  OdometryNoise noise(p, 5);
  const int n = 200000;
  Eigen::Vector3d sum_sq = Eigen::Vector3d::Zero();
  double angle_sq = 0.0;
  OdometryMeasurement truth;
  truth.p_W = {1, 2, 3};
  for (int i = 0; i < n; ++i) {
    const OdometryMeasurement m = noise.Corrupt(truth);
    sum_sq += (m.p_W - truth.p_W).cwiseAbs2();
    angle_sq += std::pow(m.q_WS.angularDistance(truth.q_WS), 2);
  }
  const Eigen::Vector3d sigma = (sum_sq / n).cwiseSqrt();
  EXPECT_TRUE(sigma.isApprox(p.normal_position_m, 0.01)) << sigma.transpose();
  // the rotation angle of a 3-axis Gaussian small rotation: E[theta^2] = 3 sigma^2
  EXPECT_NEAR(std::sqrt(angle_sq / n / 3.0), 0.017, 0.017 * 0.01);
  const auto cov = noise.PoseCovariance();
  EXPECT_DOUBLE_EQ(cov[0], 1e-4);
  EXPECT_DOUBLE_EQ(cov[7], 4e-4);
  EXPECT_DOUBLE_EQ(cov[35], 0.017 * 0.017);
}

TEST(OdometryNoise, UniformNoiseStaysWithinItsBound) {
  OdometryNoiseParams p;
  p.uniform_position_m = {0.05, 0.05, 0.05};
  OdometryNoise noise(p, 9);
  double max_err = 0.0;
  for (int i = 0; i < 10000; ++i) max_err = std::max(max_err, noise.Corrupt({}).p_W.cwiseAbs().maxCoeff());
  EXPECT_LE(max_err, 0.05);
  EXPECT_GT(max_err, 0.049);
}
