// Static obstacles for the batched flight engine: one set per environment (per vehicle) of boxes
// turned about z and upright cylinders, as clutter generators and walls make them, and optionally a
// world that every environment shares (the power plant, the warehouse: its visuals for the rays,
// its static collisions' occupancy for the spheres). Two questions are asked of them: does a
// vehicle's sphere touch one (the exact distance of a point to a box, a cylinder, an occupied cell,
// every physics step; grids keep it to what is near the vehicle), and where do a camera's rays
// first meet one (Embree 3: each environment its own scene of its obstacles' triangles, the world
// through its RayScene; 16 rays at a time). No ROS, no multirotor.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace octomap {
class OcTree;
}
namespace rotors_sim {
namespace raycast {
class RayScene;
}
}  // namespace rotors_sim

namespace rotors_flight_batch {

/// One obstacle in its environment's world frame W.
struct Obstacle {
  enum class Shape { kBox, kCylinder };
  Shape shape = Shape::kBox;
  Eigen::Vector3d center_W = Eigen::Vector3d::Zero();  ///< [m]
  /// box: half its lengths along its own axes; cylinder (axis along z): radius, radius, half height [m]
  Eigen::Vector3d half_extents_m = Eigen::Vector3d::Constant(0.5);
  double yaw_rad = 0.0;  ///< box: its turn about z (a cylinder's is ignored: it is round)
  /// "" or why the obstacle is not one (a size <= 0, a value not finite).
  std::string Validate() const;
  /// The distance [m] from point c_W to the obstacle's surface, 0 inside it (R^3's Euclidean distance).
  double Distance(const Eigen::Vector3d& c_W) const;
};

class ObstacleField {
 public:
  /// `environments` empty sets. A sphere of radius up to `max_sphere_radius_m` is tested exactly;
  /// a larger one is refused by SphereTouches' caller (FlightBatch) when it sets the field.
  ObstacleField(int environments, double max_sphere_radius_m);
  ~ObstacleField();
  ObstacleField(const ObstacleField&) = delete;
  ObstacleField& operator=(const ObstacleField&) = delete;

  int Environments() const { return static_cast<int>(sets_.size()); }
  double MaxSphereRadius() const { return max_sphere_radius_m_; }
  /// Environment `env`'s obstacles from now on (its ray scene rebuilt). SimError naming the
  /// environment and the obstacle that is not one; nothing changes then.
  void Set(int env, std::vector<Obstacle> obstacles);
  const std::vector<Obstacle>& Get(int env) const;

  /// Every environment also holds the world whose visuals `scene` casts (synced: static geometry
  /// only) and whose static collision geometry `occupied` holds (BuildOccupancy's octree: a sphere
  /// touches the world when it touches an occupied cell; the cells hold the surfaces, so a touch is
  /// found up to a cell before the surface). `keep_alive` is kept as long as the scene is used (the
  /// world the scene reads). nullptr: no world.
  void SetWorld(std::shared_ptr<const rotors_sim::raycast::RayScene> scene, const octomap::OcTree* occupied,
                std::shared_ptr<const void> keep_alive);
  bool HasWorld() const { return world_scene_ != nullptr; }
  size_t WorldOccupiedCells() const { return world_cells_; }

  /// True when a sphere at c_W of radius r_m (<= MaxSphereRadius) touches or overlaps an obstacle
  /// of environment `env`.
  bool SphereTouches(int env, const Eigen::Vector3d& c_W, double r_m) const;

  /// The distance along each of n unit rays origin_W + t dirs_W[k] to the first obstacle of `env`
  /// with t in [near_m, far_m]; +inf where there is none. Safe to call from several threads.
  void Cast(int env, const Eigen::Vector3d& origin_W, const Eigen::Vector3d* dirs_W, size_t n, double near_m,
            double far_m, double* t_m) const;

 private:
  struct Set_;
  double max_sphere_radius_m_;
  std::vector<std::unique_ptr<Set_>> sets_;
  struct Embree;
  std::unique_ptr<Embree> embree_;
  // the shared world
  std::shared_ptr<const rotors_sim::raycast::RayScene> world_scene_;
  std::shared_ptr<const void> world_keep_alive_;
  struct CellGrid;
  std::unique_ptr<CellGrid> world_grid_;
  size_t world_cells_ = 0;
  bool WorldSphereTouches(const Eigen::Vector3d& c_W, double r_m) const;
};

}  // namespace rotors_flight_batch
