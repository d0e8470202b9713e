#include "octomap_ros.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <octomap_msgs/conversions.h>

namespace rotors_planning {

octomap_msgs::Octomap ToMsg(const octomap::OcTree& tree, const std::string& frame_id, bool binary) {
  octomap_msgs::Octomap msg;
  const bool ok = binary ? octomap_msgs::binaryMapToMsg(tree, msg) : octomap_msgs::fullMapToMsg(tree, msg);
  if (!ok) ROS_ERROR("[mapping] cannot serialise the map");
  msg.header.frame_id = frame_id;
  return msg;
}

std::unique_ptr<octomap::OcTree> FromMsg(const octomap_msgs::Octomap& msg) {
  // checked before OctoMap's factory, which prints a line of its own for every unknown type
  if (msg.id != "OcTree") throw std::runtime_error("the map message holds a '" + msg.id + "', not an OcTree");
  if (!(std::isfinite(msg.resolution) && msg.resolution > 0.0))
    throw std::runtime_error("the map message's resolution " + std::to_string(msg.resolution) + " is not > 0");
  std::unique_ptr<octomap::AbstractOcTree> tree(octomap_msgs::msgToMap(msg));
  if (!tree) throw std::runtime_error("the map message (id '" + msg.id + "') does not read as an OctoMap");
  auto* octree = dynamic_cast<octomap::OcTree*>(tree.get());
  if (!octree) throw std::runtime_error("the map message holds a " + msg.id + ", not an OcTree");
  tree.release();
  return std::unique_ptr<octomap::OcTree>(octree);
}

visualization_msgs::MarkerArray OccupiedCells(const octomap::OcTree& tree, const std::string& frame_id,
                                              const ros::Time& stamp) {
  std::map<unsigned, visualization_msgs::Marker> by_depth;
  double z_min = 1e9, z_max = -1e9;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    z_min = std::min(z_min, it.getZ());
    z_max = std::max(z_max, it.getZ());
  }
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    visualization_msgs::Marker& m = by_depth[it.getDepth()];
    if (m.points.empty()) {
      m.header.frame_id = frame_id;
      m.header.stamp = stamp;
      m.ns = "occupied_cells";
      m.id = static_cast<int>(it.getDepth());
      m.type = visualization_msgs::Marker::CUBE_LIST;
      m.scale.x = m.scale.y = m.scale.z = it.getSize();
      m.pose.orientation.w = 1.0;
      m.color.a = 1.0;
    }
    geometry_msgs::Point p;
    p.x = it.getX();
    p.y = it.getY();
    p.z = it.getZ();
    m.points.push_back(p);
    // blue (low) to red (high)
    std_msgs::ColorRGBA c;
    const double h = z_max > z_min ? (p.z - z_min) / (z_max - z_min) : 0.5;
    c.r = static_cast<float>(h);
    c.g = static_cast<float>(0.3 + 0.4 * (1.0 - std::abs(2.0 * h - 1.0)));
    c.b = static_cast<float>(1.0 - h);
    c.a = 1.0f;
    m.colors.push_back(c);
  }
  visualization_msgs::MarkerArray out;
  for (auto& [depth, marker] : by_depth) out.markers.push_back(marker);
  return out;
}

Eigen::Vector3d VectorParam(const ros::NodeHandle& nh, const std::string& name, const Eigen::Vector3d& fallback) {
  if (!nh.hasParam(name)) return fallback;
  std::vector<double> v;
  if (!nh.getParam(name, v) || v.size() != 3) {
    throw std::runtime_error("parameter " + nh.resolveName(name) + " must be a list [x, y, z] of three numbers");
  }
  return {v[0], v[1], v[2]};
}

}  // namespace rotors_planning
