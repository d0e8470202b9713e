#include "rotors_planning/waypoint_file.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rotors_planning {

std::vector<Waypoint> ReadWaypointFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::invalid_argument("waypoint file '" + path + "' cannot be opened");
  std::vector<Waypoint> waypoints;
  std::string line;
  for (int number = 1; std::getline(file, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    std::istringstream fields(line);
    Waypoint w;
    double yaw_deg = 0.0;
    std::string rest;
    if (!(fields >> w.wait_time_s >> w.p_W.x() >> w.p_W.y() >> w.p_W.z() >> yaw_deg) || (fields >> rest) ||
        !std::isfinite(w.wait_time_s + w.p_W.sum() + yaw_deg) || w.wait_time_s < 0.0) {
      throw std::invalid_argument("waypoint file '" + path + "' line " + std::to_string(number) + " is '" + line +
                                  "'; expected five numbers: wait_time_s x y z yaw_deg (wait_time_s >= 0)");
    }
    w.yaw_rad = yaw_deg * M_PI / 180.0;
    waypoints.push_back(w);
  }
  if (waypoints.empty()) throw std::invalid_argument("waypoint file '" + path + "' holds no waypoint");
  return waypoints;
}

}  // namespace rotors_planning
