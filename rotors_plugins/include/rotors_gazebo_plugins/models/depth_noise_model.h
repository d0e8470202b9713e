// Axial noise of depth cameras (librotors_gazebo_noisydepth_plugin.so). Engine-free.
//   Kinect (Nguyen, Izadi, Lovell 2012, 10-60 deg model): sigma(z) = 0.0012 + 0.0019 (z - 0.4)^2  [m]
//   D435 (Intel's theoretical RMS error):                 sigma(z) = z^2 e_subpixel / (f b)       [m]
//     with f = W / (2 tan(hfov / 2)) [px], b the baseline [m], capped at max_stdev.
//   PMD (time of flight, the 1 % of distance PMD states):  sigma(z) = 0.01 z                      [m]
// Depth outside (min, max) becomes NaN.
#pragma once

#include <random>
#include <string>
#include <vector>

namespace rotors_gazebo_plugins {

struct DepthNoiseParams {
  enum class Model { kKinect, kD435, kPMD };
  Model model = Model::kKinect;
  double min_depth_m = 0.2, max_depth_m = 1000.0;
  // D435 only
  double horizontal_fov_rad = 1.5707963, baseline_m = 0.05, subpixel_error_px = 0.1, max_stdev_m = 3.0;
  int width_px = 640;
  /// "Kinect", "D435" or "PMD" (any case); throws SimError naming the value otherwise.
  static Model ParseModel(const std::string& name);
  std::string Validate() const;
};

class DepthNoiseModel {
 public:
  DepthNoiseModel(const DepthNoiseParams& params, uint64_t seed) : p_(params), rng_(seed) {}
  /// Standard deviation of the measured depth at true depth z [m].
  double Sigma(double z_m) const;
  /// Adds noise in place; NaN outside (min, max).
  void Apply(std::vector<float>* depth_m);

 private:
  DepthNoiseParams p_;
  std::mt19937_64 rng_;
  std::normal_distribution<float> normal_{0.0f, 1.0f};
};

}  // namespace rotors_gazebo_plugins
