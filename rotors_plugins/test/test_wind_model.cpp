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

// ---- custom static wind field (hemicyl format) and wind profiles ----------------------------------
#include <fstream>

#include "rotors_gazebo_plugins/models/wind_field.h"

namespace {
std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = "/tmp/rotors_wind_test_" + name;
  std::ofstream(path) << text;
  return path;
}

// 2 x 2 columns, res 10 m x 20 m; columns x = 10 m stand on 10 m terrain; 3 levels at 0, 0.5, 1 of
// the column; u = 10 level + column, w = level.
const char* kField =
    "min_x: 0\nmin_y: 0\nn_x: 2\nn_y: 2\nres_x: 10\nres_y: 20\nvertical_spacing_factors: 0 0.5 1\n"
    "bottom_z: 0 10 0 10\ntop_z: 100 110 100 110\n"
    "u: 0 1 2 3 10 11 12 13 20 21 22 23\nv: 0 0 0 0 0 0 0 0 0 0 0 0\nw: 0 0 0 0 1 1 1 1 2 2 2 2\n";
}  // namespace

TEST(WindField, TrilinearOnTheTerrainFollowingGridMatchesHandValues) {
  const WindField field = WindField::Load(WriteFile("field.txt", kField));
  Eigen::Vector3d v;
  // (5, 10, 55): columns at s = 0.1 (levels 0/50/100) and 0.9 (10/60/110): u 11, 10, 13, 12 -> 11.5
  ASSERT_TRUE(field.Velocity({5, 10, 55}, &v));
  EXPECT_TRUE(v.isApprox(Eigen::Vector3d(11.5, 0.0, 1.0), 1e-12)) << v.transpose();
  // (2, 5, 30): columns u 6, 5, 8, 7 and w 0.6, 0.4, 0.6, 0.4, weights 0.6, 0.15, 0.2, 0.05
  ASSERT_TRUE(field.Velocity({2, 5, 30}, &v));
  EXPECT_TRUE(v.isApprox(Eigen::Vector3d(6.3, 0.0, 0.56), 1e-12)) << v.transpose();
  // a grid point: its own value
  ASSERT_TRUE(field.Velocity({10, 20, 110}, &v));
  EXPECT_TRUE(v.isApprox(Eigen::Vector3d(23, 0, 2), 1e-12)) << v.transpose();
  // outside: below the terrain of a surrounding column, beyond the grid, above the top
  EXPECT_FALSE(field.Velocity({5, 10, 5}, &v));
  EXPECT_FALSE(field.Velocity({25, 10, 50}, &v));
  EXPECT_FALSE(field.Velocity({5, 10, 105}, &v));
}

TEST(WindField, BadFilesNameTheProblem) {
  const std::string text = kField;
  const auto expect_error = [](const std::string& path, const std::string& words) {
    try {
      WindField::Load(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  };
  expect_error(WriteFile("nokey.txt", text.substr(0, text.find("w:"))), "missing key 'w:'");
  std::string short_u = kField;
  short_u.replace(short_u.find("u: 0 1 2 3"), 10, "u: 0 1 2");
  expect_error(WriteFile("short.txt", short_u), "'u:' has 11 values, expected 12");
  expect_error("/nonexistent/wind.txt", "cannot be opened");
}

TEST(WindProfile, LinearInTimeHeldOutside) {
  const WindProfile p = WindProfile::Load(WriteFile("profile.txt", "# t vx vy vz\n0 0 0 0\n10 5 0 0\n\n20 5 5 0\n"));
  EXPECT_TRUE(p.Velocity(5.0).isApprox(Eigen::Vector3d(2.5, 0, 0)));
  EXPECT_TRUE(p.Velocity(15.0).isApprox(Eigen::Vector3d(5, 2.5, 0)));
  EXPECT_TRUE(p.Velocity(-1.0).isZero());
  EXPECT_TRUE(p.Velocity(30.0).isApprox(Eigen::Vector3d(5, 5, 0)));
  try {
    WindProfile::Load(WriteFile("bad_profile.txt", "0 0 0 0\n5 1 1\n"));
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad_profile.txt:2: expected 't vx vy vz', got 3 values"), std::string::npos)
        << e.what();
  }
}
