// A map built from range sensors with OctoMap's own sensor model (the role of octomap_server):
// each cloud is inserted at the sensor's position, the ray to every endpoint marks free space,
// the endpoint is a hit; endpoints beyond max_range only clear space up to max_range.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace octomap {
class OcTree;
}

namespace rotors_planning {

/// Parameters named as octomap_server names them.
struct MapBuilderParams {
  double resolution_m = 0.15;    ///< [m] `resolution`: leaf size
  double max_range_m = -1.0;     ///< [m] `sensor_model/max_range`; <= 0: no limit
  double prob_hit = 0.7;         ///< `sensor_model/hit`
  double prob_miss = 0.4;        ///< `sensor_model/miss`
  double clamping_min = 0.12;    ///< `sensor_model/min`
  double clamping_max = 0.97;    ///< `sensor_model/max`
  std::string Validate() const;  ///< empty when valid, else a one-line reason
};

class MapBuilder {
 public:
  /// Throws std::invalid_argument with Validate()'s reason.
  explicit MapBuilder(const MapBuilderParams& params);
  ~MapBuilder();

  /// Inserts the endpoints (world frame) seen from the sensor at origin_W; non-finite points are
  /// skipped (a depth camera's no-return pixels). Returns the number of points inserted.
  size_t Insert(const std::vector<Eigen::Vector3d>& points_W, const Eigen::Vector3d& origin_W);
  void Clear();

  const octomap::OcTree& Tree() const { return *tree_; }
  const MapBuilderParams& Params() const { return params_; }

 private:
  MapBuilderParams params_;
  std::unique_ptr<octomap::OcTree> tree_;
};

}  // namespace rotors_planning
