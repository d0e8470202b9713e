// A lens-distorted camera image from a pinhole rendering: for each pixel of the distorted image,
// where its ray meets a larger pinhole image of the same focal length (Gazebo renders distortion
// the same way: an undistorted image, then a remap). Engine-free: no GL.
#pragma once

#include <cstdint>
#include <vector>

#include "rotors_core/rendering/camera_model.h"

namespace rotors_sim {
namespace rendering {

class DistortionMap {
 public:
  /// For `camera` (its distortion must not be the identity); throws SimError when the pinhole image
  /// it needs would be more than 4 times the output's width or height.
  explicit DistortionMap(const CameraSpec& camera);

  /// The pinhole camera to render: the same focal length, wide enough that every output pixel's
  /// ray lands at least one pixel inside it.
  const CameraIntrinsics& Pinhole() const { return pinhole_; }

  /// The distorted image: each pixel bilinear in the pinhole image (`channels` bytes per pixel).
  void RemapImage(const std::vector<uint8_t>& pinhole, int channels, std::vector<uint8_t>* out) const;
  /// The distorted depth: the nearest pinhole pixel (depth is not blended across edges).
  void RemapDepth(const std::vector<float>& pinhole, std::vector<float>* out) const;

 private:
  CameraIntrinsics pinhole_;
  /// output pixel i = v W + u shows pinhole pixel (source_u_[i], source_v_[i])
  std::vector<float> source_u_, source_v_;
};

}  // namespace rendering
}  // namespace rotors_sim
