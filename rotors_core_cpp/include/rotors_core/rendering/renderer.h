// Renders the world's visual geometry as a camera sees it: headless OpenGL 3.3 through EGL on
// Mesa's surfaceless platform (llvmpipe), no X server. Its parts live in src/rendering: the
// context (gl_context), shader programs, GPU mesh and texture caches (gpu_cache), render targets,
// the sun's shadow map (sun_shadow); this class draws a frame with them. One renderer (and GL context, with its
// uploaded meshes) per world, kept in the world; used from the thread that steps that world. Colour is Lambert shading
// under the world's sun plus Gaussian pixel noise (a hash of pixel, frame and seed: deterministic); depth is the
// optical-axis distance written by the fragment shader as a float, so it is exact to float precision.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "rotors_core/geometry/visual.h"
#include "rotors_core/physics/physics_types.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/rendering/camera_model.h"

namespace rotors_sim {
namespace rendering {

struct RenderedFrame {
  int width_px = 0, height_px = 0;
  std::vector<uint8_t> image;  ///< rows top to bottom, BytesPerPixel(format) per pixel; empty if not asked
  std::vector<float> depth_m;  ///< optical-axis distance per pixel, NaN where nothing is in range
};

/// One camera's frame to render (Render's arguments).
struct FrameRequest {
  ignition::math::Pose3d X_WC;
  const CameraSpec* camera = nullptr;
  uint64_t noise_seed = 0;
  bool want_image = true, want_depth = false;
  RenderedFrame* out = nullptr;
};

/// Gazebo's <noise> (Gaussian, in units of full scale) on an image read back from the GPU: for a
/// distorted camera's remapped image and a frame the image sensor model made (the shader's noise
/// would be blurred by the remap, or averaged over an exposure). Deterministic in the seed.
void AddGaussianNoise(const CameraSpec& camera, uint64_t seed, std::vector<uint8_t>* image);

class Renderer {
 public:
  /// The world's renderer; creates its GL context on first use. Throws SimError when no headless
  /// OpenGL 3.3 context can be made (the message names the missing package).
  static Renderer& Of(physics::World& world);
  ~Renderer();

  /// Renders every visual of every model of `world` from the camera at X_WC (camera frame:
  /// x forward, z up). noise_seed picks the noise pattern (same seed, same image). A camera with
  /// lens distortion is a larger pinhole rendering remapped through its DistortionMap.
  void Render(const physics::World& world, const ignition::math::Pose3d& X_WC, const CameraSpec& camera,
              uint64_t noise_seed, bool want_image, bool want_depth, RenderedFrame* out);

  /// Several cameras of `world` at once (a stereo pair): each frame is the one Render gives, but a
  /// camera is drawn while the one before it is still being rasterised, so the two CPU sides of
  /// the work overlap.
  void RenderAll(const physics::World& world, const std::vector<FrameRequest>& requests);

  /// Triangles of the shapes cached now, for benchmarks.
  size_t CachedTriangles() const;
  /// Entries of each cache now; each is bounded (least recently used dropped first).
  struct CacheSizes {
    size_t meshes = 0, textures = 0, targets = 0, distortion_maps = 0;
  };
  CacheSizes CachedObjects() const;

 private:
  Renderer();
  /// Draws a pinhole camera into the render target of `slot` (one per camera of a RenderAll);
  /// ReadPinhole reads that target back.
  void DrawPinhole(const physics::World& world, const ignition::math::Pose3d& X_WC, const CameraSpec& camera,
                   uint64_t noise_seed, bool want_image, bool want_depth, size_t slot);
  void ReadPinhole(const CameraSpec& camera, bool want_image, bool want_depth, size_t slot, RenderedFrame* out);
  struct Impl;  // the GL context, shader programs, caches and shadow map (src/rendering)
  std::unique_ptr<Impl> impl_;
};

}  // namespace rendering
}  // namespace rotors_sim
