// Wind model: constant wind, a gust that acts only in its window, and real (seeded) randomness.
#include <gtest/gtest.h>

#include <cmath>

#include "rotors_gazebo_plugins/models/wind_model.h"

using namespace rotors_gazebo_plugins;

TEST(WindModel, GustActsOnlyInsideItsWindow) {
  WindParams p;
  p.wind_speed_mean_m_s = 3.0;
  p.wind_gust_start_s = 40.0;
  p.wind_gust_duration_s = 2.0;
  p.wind_gust_force_mean_n = 5.0;
  p.wind_gust_direction = {1, 1, 0};
  WindModel wind(p, 1);
  EXPECT_TRUE(wind.Sample(39.99).force_W.isZero());
  const auto during = wind.Sample(41.0);
  EXPECT_NEAR(during.force_W.norm(), 5.0, 1e-12);
  EXPECT_NEAR(during.force_W.x(), during.force_W.y(), 1e-12);
  EXPECT_TRUE(wind.Sample(42.0).force_W.isZero());
  EXPECT_TRUE(wind.Sample(0.0).velocity_W.isApprox(Eigen::Vector3d(3, 0, 0)));
}

TEST(WindModel, VarianceProducesSeededRandomness) {
  WindParams p;
  p.wind_speed_mean_m_s = 2.0;
  p.wind_speed_variance = 0.25;
  WindModel a(p, 11), b(p, 11);
  double sum = 0, sum_sq = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double s = a.Sample(i * 0.01).velocity_W.x();
    ASSERT_EQ(s, b.Sample(i * 0.01).velocity_W.x());
    sum += s;
    sum_sq += s * s;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 2.0, 0.01);
  EXPECT_NEAR(sum_sq / n - mean * mean, 0.25, 0.01);
}
