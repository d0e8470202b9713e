// Time and update information, mirroring gazebo::common::Time / UpdateInfo in names and shape.
#pragma once

#include <cstdint>
#include <string>

namespace rotors_sim {
namespace common {

/// Simulation or wall-clock time [s, ns]; integer nanoseconds so that 0.01 s steps never drift.
class Time {
 public:
  Time() = default;
  Time(int32_t sec_in, int32_t nsec_in) { Set(int64_t{sec_in} * 1000000000LL + nsec_in); }
  static Time FromNanoseconds(int64_t ns) {
    Time t;
    t.Set(ns);
    return t;
  }
  static Time FromSeconds(double s) { return FromNanoseconds(static_cast<int64_t>(s * 1e9 + (s >= 0 ? 0.5 : -0.5))); }

  double Double() const { return static_cast<double>(ns_) * 1e-9; }
  int64_t Nanoseconds() const { return ns_; }

  Time operator+(const Time& o) const { return FromNanoseconds(ns_ + o.ns_); }
  Time operator-(const Time& o) const { return FromNanoseconds(ns_ - o.ns_); }
  bool operator<(const Time& o) const { return ns_ < o.ns_; }
  bool operator<=(const Time& o) const { return ns_ <= o.ns_; }
  bool operator>(const Time& o) const { return ns_ > o.ns_; }
  bool operator>=(const Time& o) const { return ns_ >= o.ns_; }
  bool operator==(const Time& o) const { return ns_ == o.ns_; }

  int32_t sec = 0;   ///< whole seconds (Gazebo field name)
  int32_t nsec = 0;  ///< nanoseconds in [0, 1e9) (Gazebo field name)

 private:
  void Set(int64_t ns) {
    ns_ = ns;
    int64_t s = ns / 1000000000LL, r = ns % 1000000000LL;
    if (r < 0) {
      r += 1000000000LL;
      --s;
    }
    sec = static_cast<int32_t>(s);
    nsec = static_cast<int32_t>(r);
  }
  int64_t ns_ = 0;
};

/// Passed to world-update callbacks (gazebo::common::UpdateInfo).
struct UpdateInfo {
  std::string worldName;
  Time simTime;   ///< simulation time at the start of this step
  Time realTime;  ///< wall-clock time since the world started
};

}  // namespace common
}  // namespace rotors_sim
