// The one policy of every parameter reader (plugins' SDF, controllers' and the estimator's ROS
// parameters): remember each name the code asked for, so that a parameter nobody reads (a typo,
// a key of another plugin) is reported by name instead of silently ignored.
#pragma once

#include <set>
#include <string>
#include <vector>

namespace rotors_params {

class ParamRecord {
 public:
  void Asked(const std::string& name) { asked_.insert(name); }
  bool WasAsked(const std::string& name) const { return asked_.count(name) > 0; }
  bool Empty() const { return asked_.empty(); }
  /// The names of `present` nobody asked for, in their order.
  std::vector<std::string> Unasked(const std::vector<std::string>& present) const {
    std::vector<std::string> out;
    for (const std::string& name : present)
      if (!WasAsked(name)) out.push_back(name);
    return out;
  }
  /// "a, b, c": the names asked for.
  std::string AskedList() const {
    std::string list;
    for (const std::string& name : asked_) list += (list.empty() ? "" : ", ") + name;
    return list;
  }

 private:
  std::set<std::string> asked_;
};

}  // namespace rotors_params
