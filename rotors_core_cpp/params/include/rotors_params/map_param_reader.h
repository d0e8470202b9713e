// The parameter policy of RosParamReader (ParamRecord) over a flat map of names such as
// "rotor_configuration/0/angle" to numbers, with no ROS: the Python module reads the same
// controller and vehicle yaml files into such a map. Same methods, same messages.
#pragma once

#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "rotors_params/param_record.h"

namespace rotors_params {

class MapParamReader {
 public:
  /// `numbers`: name -> value; `others`: names present with a value that is not a number.
  /// `source` names where the map came from (in messages), e.g. "lee_controller_firefly.yaml".
  MapParamReader(std::map<std::string, double> numbers, std::set<std::string> others, std::string source)
      : numbers_(std::move(numbers)), others_(std::move(others)), source_(std::move(source)) {}

  std::string Require(const std::string& name, double* value, const std::string& hint) {
    record_.Asked(name);
    if (Read(name, value)) return {};
    if (others_.count(name)) return "parameter " + Resolve(name) + " must be a number";
    return "missing parameter " + Resolve(name) + " (" + hint + ")";
  }
  std::string Optional(const std::string& name, double* value, const std::string& meaning) {
    record_.Asked(name);
    if (Read(name, value)) return {};
    if (others_.count(name)) return "parameter " + Resolve(name) + " must be a number";
    std::ostringstream line;
    line << Resolve(name) << " not given: " << *value << " (" << meaning << ")";
    defaults_.push_back(line.str());
    return {};
  }
  std::string RequireVector(const std::string& name, Eigen::Vector3d* value, const std::string& hint) {
    const char* axes[3] = {"x", "y", "z"};
    for (const char* axis : axes) record_.Asked(name + "/" + axis);
    if (!Has(name)) return "missing parameter " + Resolve(name) + " (" + hint + ")";
    for (int i = 0; i < 3; ++i)
      if (!Read(name + "/" + axes[i], &(*value)[i])) return "parameter " + Resolve(name) + " needs numbers x, y and z";
    return {};
  }
  /// The name itself or anything below it is present.
  bool Has(const std::string& name) const {
    if (numbers_.count(name)) return true;
    auto below = numbers_.lower_bound(name + "/");
    if (below != numbers_.end() && below->first.compare(0, name.size() + 1, name + "/") == 0) return true;
    for (const std::string& other : others_)
      if (other == name || other.compare(0, name.size() + 1, name + "/") == 0) return true;
    return false;
  }
  std::string Resolve(const std::string& name) const { return name + " (" + source_ + ")"; }
  /// Names in the map nobody asked for.
  std::vector<std::string> UnknownKeys() const {
    std::vector<std::string> present;
    for (const auto& number : numbers_) present.push_back(number.first);
    present.insert(present.end(), others_.begin(), others_.end());
    return record_.Unasked(present);
  }
  const std::vector<std::string>& Defaults() const { return defaults_; }

 private:
  bool Read(const std::string& name, double* value) const {
    auto it = numbers_.find(name);
    if (it == numbers_.end()) return false;
    *value = it->second;
    return true;
  }
  std::map<std::string, double> numbers_;
  std::set<std::string> others_;
  std::string source_;
  ParamRecord record_;
  std::vector<std::string> defaults_;
};

}  // namespace rotors_params
