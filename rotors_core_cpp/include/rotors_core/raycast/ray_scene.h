// The world's visual geometry as a ray-casting scene (Embree 3): what laser sensors hit. Every
// shape's acceleration structure (a unit box, sphere, cylinder or square, a mesh, a heightmap, an
// OctoMap's exposed faces) is built once; each visual is an instance of its shape, placed by its
// link's pose. Sync() moves the instances whose links moved and adds or drops those of models
// spawned or removed, so a cast sees the world of the last step: static geometry, other vehicles
// and the caster's own body alike.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>

#include <Eigen/Core>

#include "rotors_core/physics/physics_types.h"

namespace rotors_sim {
namespace raycast {

/// The first surface along a ray.
struct RayHit {
  double distance_m = std::numeric_limits<double>::infinity();  ///< +inf: nothing within [near, far]
  Eigen::Vector3d normal_W = Eigen::Vector3d::Zero();           ///< unit, facing the ray's origin
  const physics::Link* link = nullptr;                          ///< whose visual was hit
  bool Hit() const { return distance_m < std::numeric_limits<double>::infinity(); }
};

class RayScene {
 public:
  /// A scene of `world`'s visuals; it reads the world at each Sync() and must not outlive it.
  explicit RayScene(const physics::World& world);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  /// Brings the scene to the world's state now (cheap when nothing moved since the last call).
  void Sync();

  /// The first surface along origin_W + t dir_W (dir_W a unit vector) with t in [near_m, far_m],
  /// skipping the visuals of link `ignore` (nullptr: skip none). A caster that skips the same link
  /// on every ray passes the mask SkipMask(link) gave it: the link's visuals are then left out by
  /// Embree's ray mask, which costs nothing, instead of by a filter called on every candidate hit.
  RayHit Cast(const Eigen::Vector3d& origin_W, const Eigen::Vector3d& dir_W, double near_m, double far_m,
              const physics::Link* ignore = nullptr, uint32_t ray_mask = kAllVisuals) const;
  /// Cast for n rays from one origin (a lidar's column), 16 at a time through Embree's ray packets:
  /// hits[k] for dirs_W[k]. Same results as n calls of Cast, faster for rays that stay together.
  void CastFan(const Eigen::Vector3d& origin_W, const Eigen::Vector3d* dirs_W, size_t n, double near_m, double far_m,
               const physics::Link* ignore, uint32_t ray_mask, RayHit* hits) const;
  /// A ray mask that leaves out `link`'s visuals (one of 31 bits, reserved for the link on the first
  /// call); kAllVisuals when the bits are used up: Cast then skips the link with the filter.
  uint32_t SkipMask(const physics::Link* link);
  static constexpr uint32_t kAllVisuals = 0xFFFFFFFFu;

  size_t InstanceCount() const;
  size_t TriangleCount() const;  ///< of all shapes built so far (spheres are exact, not triangles)
  /// The Embree RTCScene behind Cast (opaque here), for benchmarks that call Embree directly.
  void* EmbreeScene() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace raycast
}  // namespace rotors_sim
