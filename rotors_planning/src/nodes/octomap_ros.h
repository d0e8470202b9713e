// ROS glue shared by the mapping and planner nodes: OcTree <-> octomap_msgs, occupied cells as
// rviz cubes (octomap_server's occupied_cells_vis_array), parameters read with one-line errors.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <octomap/OcTree.h>
#include <octomap_msgs/Octomap.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

namespace rotors_planning {

/// The tree as a message, or nullptr-like empty map on failure (logged).
octomap_msgs::Octomap ToMsg(const octomap::OcTree& tree, const std::string& frame_id, bool binary);
/// An OcTree from a message; throws std::runtime_error naming the problem (not an OcTree, bad data).
std::unique_ptr<octomap::OcTree> FromMsg(const octomap_msgs::Octomap& msg);
/// Occupied leaves as one CUBE_LIST per leaf size (coloured by height), as octomap_server.
visualization_msgs::MarkerArray OccupiedCells(const octomap::OcTree& tree, const std::string& frame_id,
                                              const ros::Time& stamp);
/// A 3-vector parameter given as [x, y, z]; throws std::runtime_error naming the parameter.
Eigen::Vector3d VectorParam(const ros::NodeHandle& nh, const std::string& name, const Eigen::Vector3d& fallback);

}  // namespace rotors_planning
