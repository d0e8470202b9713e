// RotorS' waypoint files (waypoint_publisher_file): one waypoint per line, "wait_time x y z yaw_deg"
// ([s], [m], [deg]); the next waypoint is sent wait_time after this one.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace rotors_planning {

struct Waypoint {
  double wait_time_s = 0.0;
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
};

/// Throws std::invalid_argument naming the file and line for a missing file or a malformed line.
std::vector<Waypoint> ReadWaypointFile(const std::string& path);

}  // namespace rotors_planning
