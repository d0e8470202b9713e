// rviz markers of what the engine keeps for drawing: the visuals of static models (boxes,
// spheres, cylinders, planes, meshes as triangle lists, heightmaps, OctoMaps as cube lists).
// Moving models are drawn by rviz' RobotModel from robot_description; they are left out here.
#pragma once

#include <string>

#include <octomap/OcTree.h>
#include <visualization_msgs/MarkerArray.h>

#include "rotors_core/physics/world.h"

namespace rotors_sim {

/// One marker per visual of every static model, in frame `frame_id` (the world frame).
visualization_msgs::MarkerArray WorldMarkers(const physics::World& world, const std::string& frame_id);

/// The occupied leaves of `tree` as a CUBE_LIST at the tree's resolution (larger pruned leaves are
/// split), coloured by height from blue (low) to red (high), moved by `offset_m`.
visualization_msgs::Marker OcTreeCubes(const octomap::OcTree& tree, const std::string& frame_id, const std::string& ns,
                                       const octomap::point3d& offset_m = {0, 0, 0});

}  // namespace rotors_sim
