// The sun's shadow map around a camera's view: depth seen from the sun (orthographic), and the
// transform from the world to its coordinates (s, t, depth, each 0..1 over the map). Static
// models' casters are drawn into one layer, again only when the region moves or one of them is
// moved; the other models' (vehicles) into a second, coarser layer, again whenever they move.
#pragma once

#include <Eigen/Core>

#include "rendering/gl.h"
#include "rendering/gpu_cache.h"
#include "rendering/shader_programs.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/rendering/camera_model.h"

namespace rotors_sim {
namespace rendering {

/// Depth seen from the sun over the map's region, drawn from some of the models' visuals; owns its
/// texture and framebuffer.
struct ShadowLayer {
  explicit ShadowLayer(int texels_per_side) : texels(texels_per_side) {}
  ShadowLayer(const ShadowLayer&) = delete;
  ShadowLayer& operator=(const ShadowLayer&) = delete;
  ~ShadowLayer();
  int texels = 0;  // per side
  GLuint fbo = 0, depth = 0;
  size_t drawn_for = 0;  // SceneKey of what it was last drawn from; 0: nothing yet
  bool empty = true;     // no caster in the region
};

class SunShadow {
 public:
  static constexpr int kTexels = 2048;              // per side, the static layer
  static constexpr int kMovingTexels = 1024;        // per side, the layer of the other models
  static constexpr double kViewDistance_m = 30.0;   // shadows are drawn up to this far from a camera
  static constexpr double kCastersAbove_m = 200.0;  // casters this far towards the sun beyond the view still count
  static constexpr int kSnapTexels = 32;            // the map moves in steps of this many texels

  SunShadow(const ShaderPrograms& programs, MeshCache* meshes) : programs_(programs), meshes_(*meshes) {}

  /// Updates the map for a camera at X_WC, redrawing a layer unless the one drawn last covers the
  /// same region of the same scene (the other camera of a stereo pair, usually); false when the
  /// world has no shadows.
  bool Update(const physics::World& world, const ignition::math::Pose3d& X_WC, const CameraIntrinsics& in);

  const ShadowLayer& Fixed() const { return fixed_; }
  const ShadowLayer& Moving() const { return moving_; }
  /// World -> shadow-map coordinates of the last Update.
  const Eigen::Matrix4d& T_SW() const { return T_SW_; }

 private:
  /// Clears a layer and draws the casting visuals of the static models (or of the others) into it.
  void DrawCasters(const physics::World& world, const Eigen::Matrix4d& T_clip_W, bool static_models,
                   ShadowLayer* layer);

  const ShaderPrograms& programs_;
  MeshCache& meshes_;
  ShadowLayer fixed_{kTexels}, moving_{kMovingTexels};
  Eigen::Vector3d region_centre_L_ = Eigen::Vector3d::Zero();  // in the sun's frame
  double region_half_m_ = 0.0;                                 // 0: no region yet
  Eigen::Matrix4d T_SW_ = Eigen::Matrix4d::Identity();
};

}  // namespace rendering
}  // namespace rotors_sim
