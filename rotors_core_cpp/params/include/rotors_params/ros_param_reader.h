// Reading a node's private ROS parameters under the project's policy (ParamRecord): a missing
// required parameter is one line naming it, an optional one that is absent is announced with the
// value used, and a key below the node that nobody asked for is reported by name (a typo, such as
// RotorS' `core/fixed_bias`, would otherwise go unnoticed). Used by the controllers and the estimator.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <ros/ros.h>

#include "rotors_params/param_record.h"

namespace rotors_params {

class RosParamReader {
 public:
  explicit RosParamReader(const ros::NodeHandle& nh) : nh_(nh) {}

  /// "" or "missing parameter <full name> (<hint>)" / "... must be a number".
  std::string Require(const std::string& name, double* value, const std::string& hint) {
    Ask(name);
    if (nh_.getParam(name, *value)) return {};
    if (nh_.hasParam(name)) return "parameter " + nh_.resolveName(name) + " must be a number";
    return "missing parameter " + nh_.resolveName(name) + " (" + hint + ")";
  }
  /// Keeps *value when absent (announced in Defaults(), with `meaning`); "" or why it is bad.
  std::string Optional(const std::string& name, double* value, const std::string& meaning) {
    Ask(name);
    if (nh_.getParam(name, *value)) return {};
    if (nh_.hasParam(name)) return "parameter " + nh_.resolveName(name) + " must be a number";
    std::ostringstream line;
    line << nh_.resolveName(name) << " not given: " << *value << " (" << meaning << ")";
    defaults_.push_back(line.str());
    return {};
  }
  /// Any type ROS reads, with a default that is announced when used (the estimator's parameters
  /// all have defaults, as upstream MSF).
  template <typename T>
  T Get(const std::string& name, const T& fallback) {
    Ask(name);
    T value = fallback;
    if (nh_.getParam(name, value)) return value;
    std::ostringstream line;
    line << name << " = " << std::boolalpha << fallback;
    defaults_.push_back(line.str());
    return fallback;
  }
  /// A gain {x, y, z}; "" or the reason.
  std::string RequireVector(const std::string& name, Eigen::Vector3d* value, const std::string& hint) {
    const char* axes[3] = {"x", "y", "z"};
    for (const char* axis : axes) Ask(name + "/" + axis);
    if (!nh_.hasParam(name)) return "missing parameter " + nh_.resolveName(name) + " (" + hint + ")";
    for (int i = 0; i < 3; ++i)
      if (!nh_.getParam(name + "/" + axes[i], (*value)[i]))
        return "parameter " + nh_.resolveName(name) + " needs numbers x, y and z";
    return {};
  }
  bool Has(const std::string& name) const { return nh_.hasParam(name); }
  std::string Resolve(const std::string& name) const { return nh_.resolveName(name); }

  /// Parameters below the node handle (or below its sub-namespaces `under`, e.g. {"core", "pose_sensor"})
  /// that nobody asked for (full names).
  std::vector<std::string> UnknownKeys(const std::vector<std::string>& under = {""}) const {
    std::vector<std::string> all, below;
    if (!nh_.getParamNames(all)) return {};
    for (const std::string& ns : under) {
      const std::string prefix = (ns.empty() ? nh_.getNamespace() : nh_.resolveName(ns)) + "/";
      for (const std::string& name : all)
        if (name.compare(0, prefix.size(), prefix) == 0) below.push_back(name);
    }
    return record_.Unasked(below);
  }
  /// The announcements of absent optional parameters, in the order asked.
  const std::vector<std::string>& Defaults() const { return defaults_; }

 private:
  void Ask(const std::string& name) { record_.Asked(nh_.resolveName(name)); }
  ros::NodeHandle nh_;
  ParamRecord record_;
  std::vector<std::string> defaults_;
};

}  // namespace rotors_params
