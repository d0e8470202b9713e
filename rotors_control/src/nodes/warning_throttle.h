// One warning per kind per period, where the kind is the text with its numbers left out: a flood of
// one bad input is throttled without hiding another (a single ROS_WARN_THROTTLE call site would
// print only the first of several bad messages that arrive within its period).
#pragma once

#include <cctype>
#include <map>
#include <string>

#include <ros/ros.h>

namespace rotors_control {

class WarningThrottle {
 public:
  explicit WarningThrottle(double period_s) : period_s_(period_s) {}
  /// True when a warning of this kind was not printed within the period (the caller prints it).
  bool Due(const std::string& text) {
    std::string kind;
    for (char c : text)
      if (!std::isdigit(static_cast<unsigned char>(c))) kind += c;
    const double now_s = ros::WallTime::now().toSec();
    const auto it = last_s_.find(kind);
    if (it != last_s_.end() && now_s - it->second < period_s_) return false;
    last_s_[kind] = now_s;
    return true;
  }

 private:
  double period_s_;
  std::map<std::string, double> last_s_;  ///< wall time of the last warning of each kind
};

}  // namespace rotors_control
