#include "rotors_gazebo_plugins/models/depth_noise_model.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "rotors_core/error.h"

namespace rotors_gazebo_plugins {

DepthNoiseParams::Model DepthNoiseParams::ParseModel(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == "kinect") return Model::kKinect;
  if (lower == "d435") return Model::kD435;
  if (lower == "pmd") return Model::kPMD;
  throw rotors_sim::SimError("depthNoiseModelName '" + name + "' is not a model (Kinect, D435 or PMD)");
}

std::string DepthNoiseParams::Validate() const {
  if (!(min_depth_m >= 0.0 && max_depth_m > min_depth_m)) return "need 0 <= min depth < max depth";
  if (model == Model::kD435 && !(baseline_m > 0 && horizontal_fov_rad > 0 && horizontal_fov_rad < M_PI &&
                                 subpixel_error_px >= 0 && max_stdev_m > 0 && width_px > 0))
    return "D435 noise needs baseline > 0, 0 < horizontal_fov < pi, D435NoiseSubpixelErr >= 0, D435MaxStdev > 0";
  return "";
}

double DepthNoiseModel::Sigma(double z) const {
  if (p_.model == DepthNoiseParams::Model::kKinect) return 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
  if (p_.model == DepthNoiseParams::Model::kPMD) return 0.01 * z;
  const double f_px = p_.width_px / (2.0 * std::tan(p_.horizontal_fov_rad / 2.0));
  return std::min(z * z * p_.subpixel_error_px / (f_px * p_.baseline_m), p_.max_stdev_m);
}

void DepthNoiseModel::Apply(std::vector<float>* depth_m) {
  for (float& z : *depth_m) {
    if (std::isnan(z) || z <= p_.min_depth_m || z >= p_.max_depth_m) {
      z = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    z += static_cast<float>(Sigma(z)) * normal_(rng_);
  }
}

}  // namespace rotors_gazebo_plugins
