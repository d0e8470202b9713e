// Depth noise models against their formulas: the sample standard deviation of a flat depth
// matches sigma(z), the mean stays at z, out-of-range depth is NaN, the same seed repeats.
#include <gtest/gtest.h>

#include <cmath>

#include "rotors_core/error.h"
#include "rotors_gazebo_plugins/models/depth_noise_model.h"

using namespace rotors_gazebo_plugins;

namespace {
void ExpectStatistics(const DepthNoiseParams& p, double z, double sigma_expected) {
  DepthNoiseModel model(p, 7);
  EXPECT_NEAR(model.Sigma(z), sigma_expected, 1e-12);
  std::vector<float> depth(200000, static_cast<float>(z));
  model.Apply(&depth);
  double sum = 0, sum2 = 0;
  for (float d : depth) {
    sum += d;
    sum2 += static_cast<double>(d) * d;
  }
  const double mean = sum / depth.size(), sigma = std::sqrt(sum2 / depth.size() - mean * mean);
  EXPECT_NEAR(mean, z, 4 * sigma_expected / std::sqrt(depth.size()) + 1e-6);
  EXPECT_NEAR(sigma, sigma_expected, 0.02 * sigma_expected);
}
}  // namespace

TEST(DepthNoiseModel, KinectSigmaIsNguyensAxialModel) {
  DepthNoiseParams p;
  p.max_depth_m = 10;
  // sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2
  ExpectStatistics(p, 1.0, 0.0012 + 0.0019 * 0.36);
  ExpectStatistics(p, 3.0, 0.0012 + 0.0019 * 6.76);
}

TEST(DepthNoiseModel, D435SigmaIsTheRmsErrorFormula) {
  DepthNoiseParams p;
  p.model = DepthNoiseParams::ParseModel("d435");
  p.max_depth_m = 10;
  p.width_px = 848;
  p.horizontal_fov_rad = 1.5;
  p.baseline_m = 0.05;
  p.subpixel_error_px = 0.08;
  const double f = 848 / (2 * std::tan(0.75));
  // sigma(z) = z^2 e / (f b)
  ExpectStatistics(p, 2.0, 4.0 * 0.08 / (f * 0.05));
  p.max_stdev_m = 0.01;
  EXPECT_DOUBLE_EQ(DepthNoiseModel(p, 1).Sigma(8.0), 0.01);  // capped
}

TEST(DepthNoiseModel, PmdSigmaIsOnePercentOfDistance) {
  DepthNoiseParams p;
  p.model = DepthNoiseParams::ParseModel("PMD");
  p.max_depth_m = 10;
  ExpectStatistics(p, 2.5, 0.025);  // sigma(z) = 0.01 z
}

TEST(DepthNoiseModel, OutOfRangeIsNanAndTheSeedRepeats) {
  DepthNoiseParams p;
  p.min_depth_m = 0.5;
  p.max_depth_m = 4.0;
  std::vector<float> a = {0.3f, 1.0f, 2.0f, 5.0f, NAN}, b = a;
  DepthNoiseModel(p, 3).Apply(&a);
  DepthNoiseModel(p, 3).Apply(&b);
  EXPECT_TRUE(std::isnan(a[0]) && std::isnan(a[3]) && std::isnan(a[4]));
  EXPECT_EQ(a[1], b[1]);
  EXPECT_EQ(a[2], b[2]);
  EXPECT_THROW(DepthNoiseParams::ParseModel("Lidar"), rotors_sim::SimError);
}
