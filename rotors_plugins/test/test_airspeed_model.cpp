// The airspeed sensor (the seed's eq. 19 and Note 10) against hand values: v_air = v_wind - v in the
// body frame, the pitot variant along one body axis, the noise's sigma, bad parameters.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "rotors_gazebo_plugins/models/airspeed_model.h"

using namespace rotors_gazebo_plugins;

namespace {
Eigen::Matrix3d Yaw(double psi) { return Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }
}  // namespace

TEST(AirspeedModel, IsWindMinusVelocityInTheBodyFrame) {
  AirspeedModel sensor(AirspeedParams(), 1);
  // flying along world x at 1 m/s into... a tailwind of 3 m/s along x, nose along world y (yaw 90 deg):
  // v_air_W = (2, 0, 0); the body's x is the world's y, so the air comes from the body's right: (0, -2, 0)
  const Eigen::Vector3d v_air_B = sensor.Measure(Yaw(M_PI / 2), {1, 0, 0}, {3, 0, 0});
  EXPECT_NEAR(v_air_B.x(), 0.0, 1e-12);
  EXPECT_NEAR(v_air_B.y(), -2.0, 1e-12);
  EXPECT_NEAR(v_air_B.z(), 0.0, 1e-12);
  // hovering in still air reads nothing; climbing at 2 m/s reads 2 m/s coming from above
  EXPECT_TRUE(sensor.Measure(Yaw(0.3), {0, 0, 0}, {0, 0, 0}).isZero());
  EXPECT_NEAR(sensor.Measure(Yaw(0.3), {0, 0, 2}, {0, 0, 0}).z(), -2.0, 1e-12);
}

TEST(AirspeedModel, APitotTubeSeesOnlyItsAxis) {
  AirspeedParams p;
  p.pitot_axis_B = {2, 0, 0};  // normalised by the model
  AirspeedModel pitot(p, 1);
  // head wind of 5 m/s on a level MAV pointing into it, plus a side wind the tube does not sense
  const Eigen::Vector3d m = pitot.Measure(Yaw(0.0), {0, 0, 0}, {-5, 4, 0});
  EXPECT_NEAR(m.x(), -5.0, 1e-12);
  EXPECT_NEAR(m.y(), 0.0, 1e-12);
  EXPECT_NEAR(m.z(), 0.0, 1e-12);
}

TEST(AirspeedModel, NoiseHasTheDeclaredSigmaAndRepeatsWithTheSeed) {
  AirspeedParams p;
  p.noise_stddev_m_s = 0.3;
  AirspeedModel a(p, 42), b(p, 42);
  const int n = 20000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d m = a.Measure(Yaw(0.0), {0, 0, 0}, {1, 0, 0});
    EXPECT_EQ(m, b.Measure(Yaw(0.0), {0, 0, 0}, {1, 0, 0}));
    sum += m.x() - 1.0;
    sum2 += (m.x() - 1.0) * (m.x() - 1.0);
  }
  const double mean = sum / n, sigma = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(sigma, 0.3, 0.05 * 0.3);
  EXPECT_NEAR(mean, 0.0, 4 * 0.3 / std::sqrt(n));
}

TEST(AirspeedModel, BadParametersAreNamed) {
  AirspeedParams p;
  p.noise_stddev_m_s = -1;
  EXPECT_NE(p.Validate().find("noiseStdDev -1"), std::string::npos);
  p.noise_stddev_m_s = 0;
  p.pitot_axis_B.x() = NAN;
  EXPECT_NE(p.Validate().find("pitotAxis"), std::string::npos);
}
