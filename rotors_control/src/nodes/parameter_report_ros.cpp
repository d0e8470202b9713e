#include "rotors_control/parameter_report_ros.h"

#include <sstream>

namespace rotors_control {

void ReportParameters(const ParameterReader& reader, const std::string& tag) {
  for (const std::string& line : reader.Defaults()) ROS_INFO("[%s] %s", tag.c_str(), line.c_str());
  const std::vector<std::string> unknown = reader.UnknownKeys();
  if (unknown.empty()) return;
  std::string names;
  for (const std::string& name : unknown) names += (names.empty() ? "" : ", ") + name;
  ROS_WARN("[%s] unknown parameter(s), not used: %s (a typo?)", tag.c_str(), names.c_str());
}

}  // namespace rotors_control
