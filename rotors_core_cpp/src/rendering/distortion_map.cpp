#include "rotors_core/rendering/distortion_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rotors_core/error.h"

namespace rotors_sim {
namespace rendering {

DistortionMap::DistortionMap(const CameraSpec& camera) {
  const CameraIntrinsics& in = camera.intrinsics;
  const int width_px = in.width_px, height_px = in.height_px;
  const double f = in.FocalLengthPx(), cx = in.Cx(), cy = in.Cy();
  const size_t n = static_cast<size_t>(width_px) * height_px;
  // the ideal (pinhole) point of every output pixel: x = undistort((u - cx) / f, (v - cy) / f)
  std::vector<Eigen::Vector2d> ideal(n);
  Eigen::Vector2d lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max()), hi = -lo;
  for (int v = 0; v < height_px; ++v)
    for (int u = 0; u < width_px; ++u) {
      Eigen::Vector2d x;
      if (!camera.distortion.Undistort(Eigen::Vector2d((u - cx) / f, (v - cy) / f), &x))
        throw SimError("camera '" + camera.name + "': distortion has no undistorted preimage for pixel (" +
                       std::to_string(u) + ", " + std::to_string(v) + "): coefficients out of range");
      ideal[static_cast<size_t>(v) * width_px + u] = x;
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  // pinhole pixel u' = cx' + f x, with two pixels of margin on each side for the bilinear taps
  const double margin_px = 2.0;
  const int W = static_cast<int>(std::ceil(f * (hi.x() - lo.x()) + 2 * margin_px)) + 1;
  const int H = static_cast<int>(std::ceil(f * (hi.y() - lo.y()) + 2 * margin_px)) + 1;
  if (W > 4 * width_px || H > 4 * height_px)
    throw SimError("camera '" + camera.name + "': its distortion needs a pinhole image of " + std::to_string(W) +
                   " x " + std::to_string(H) + " px to fill " + std::to_string(width_px) + " x " +
                   std::to_string(height_px) + " (more than 4 times): coefficients out of range");
  const double cx_pinhole = margin_px - f * lo.x(), cy_pinhole = margin_px - f * lo.y();
  pinhole_ = in;
  pinhole_.width_px = W;
  pinhole_.height_px = H;
  pinhole_.horizontal_fov_rad = 2.0 * std::atan(W / (2.0 * f));  // f = W / (2 tan(hfov / 2)) kept
  pinhole_.center_u = (cx_pinhole + 0.5) / W;                    // c = center W - 1/2
  pinhole_.center_v = (cy_pinhole + 0.5) / H;
  source_u_.resize(n);
  source_v_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    source_u_[i] = static_cast<float>(cx_pinhole + f * ideal[i].x());
    source_v_[i] = static_cast<float>(cy_pinhole + f * ideal[i].y());
  }
}

void DistortionMap::RemapImage(const std::vector<uint8_t>& pinhole, int channels, std::vector<uint8_t>* out) const {
  const int W = pinhole_.width_px;
  out->resize(source_u_.size() * channels);
  for (size_t i = 0; i < source_u_.size(); ++i) {
    const int u0 = static_cast<int>(std::floor(source_u_[i])), v0 = static_cast<int>(std::floor(source_v_[i]));
    const float a = source_u_[i] - u0, b = source_v_[i] - v0;
    const uint8_t* p00 = &pinhole[(static_cast<size_t>(v0) * W + u0) * channels];
    const uint8_t* p10 = p00 + channels;
    const uint8_t* p01 = p00 + static_cast<size_t>(W) * channels;
    const uint8_t* p11 = p01 + channels;
    for (int c = 0; c < channels; ++c) {
      const float value = (1 - b) * ((1 - a) * p00[c] + a * p10[c]) + b * ((1 - a) * p01[c] + a * p11[c]);
      (*out)[i * channels + c] = static_cast<uint8_t>(std::min(255.0f, value + 0.5f));
    }
  }
}

void DistortionMap::RemapDepth(const std::vector<float>& pinhole, std::vector<float>* out) const {
  const int W = pinhole_.width_px;
  out->resize(source_u_.size());
  for (size_t i = 0; i < source_u_.size(); ++i) {
    const auto u = static_cast<size_t>(std::lround(source_u_[i])), v = static_cast<size_t>(std::lround(source_v_[i]));
    (*out)[i] = pinhole[v * W + u];
  }
}

}  // namespace rendering
}  // namespace rotors_sim
