#include "rotors_planning/map_builder.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <octomap/OcTree.h>

namespace rotors_planning {

std::string MapBuilderParams::Validate() const {
  std::ostringstream why;
  if (!(resolution_m > 0.0)) {
    why << "resolution = " << resolution_m << " must be > 0 m";
  } else if (!(prob_hit > 0.5 && prob_hit <= 1.0)) {
    why << "sensor_model/hit = " << prob_hit << " must be in (0.5, 1]";
  } else if (!(prob_miss >= 0.0 && prob_miss < 0.5)) {
    why << "sensor_model/miss = " << prob_miss << " must be in [0, 0.5)";
  } else if (!(clamping_min > 0.0 && clamping_min < clamping_max && clamping_max < 1.0)) {
    why << "sensor_model/min = " << clamping_min << " and sensor_model/max = " << clamping_max
        << " must satisfy 0 < min < max < 1";
  } else if (std::isnan(max_range_m)) {
    why << "sensor_model/max_range is NaN; use a range in m, or -1 for no limit";
  }
  return why.str();
}

MapBuilder::MapBuilder(const MapBuilderParams& params) : params_(params) {
  const std::string why = params.Validate();
  if (!why.empty()) throw std::invalid_argument(why);
  Clear();
}

MapBuilder::~MapBuilder() = default;

void MapBuilder::Clear() {
  tree_ = std::make_unique<octomap::OcTree>(params_.resolution_m);
  tree_->setProbHit(params_.prob_hit);
  tree_->setProbMiss(params_.prob_miss);
  tree_->setClampingThresMin(params_.clamping_min);
  tree_->setClampingThresMax(params_.clamping_max);
}

size_t MapBuilder::Insert(const std::vector<Eigen::Vector3d>& points_W, const Eigen::Vector3d& origin_W) {
  if (!origin_W.allFinite()) return 0;
  octomap::Pointcloud cloud;
  cloud.reserve(points_W.size());
  for (const Eigen::Vector3d& p : points_W) {
    if (p.allFinite()) cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  }
  const octomap::point3d origin(origin_W.x(), origin_W.y(), origin_W.z());
  // discretize: one ray per endpoint cell (as octomap_server), each cell updated once per cloud
  tree_->insertPointCloud(cloud, origin, params_.max_range_m, /*lazy_eval=*/false, /*discretize=*/true);
  return cloud.size();
}

}  // namespace rotors_planning
