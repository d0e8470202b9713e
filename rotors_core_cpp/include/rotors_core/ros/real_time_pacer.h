// Holds the simulation to a real-time factor: sim time advances at rtf x wall time (0: unpaced).
#pragma once

#include <chrono>

#include "rotors_core/common.h"

namespace rotors_sim {

class RealTimePacer {
 public:
  explicit RealTimePacer(double real_time_factor = 1.0) : rtf_(real_time_factor) {}
  void SetRealTimeFactor(double rtf) { rtf_ = rtf; }
  double RealTimeFactor() const { return rtf_; }
  /// Restart the reference (after a pause, reset or factor change).
  void Restart(const common::Time& sim_time);
  /// Sleeps until the wall time at which `sim_time` is due.
  void WaitUntilDue(const common::Time& sim_time);

 private:
  double rtf_;
  common::Time sim_start_;
  std::chrono::steady_clock::time_point wall_start_;
};

/// For streams that people and rviz watch (/clock to other processes, TF, joint states): due at most
/// `max_rate_hz` times per wall second (<= 0: always). Faster than real time, publishing every step
/// would cost more than the physics and the controller together (a TCP send per step and
/// subscriber, and a woken subscriber process); at real time the limit does not bind.
class WallRateLimit {
 public:
  explicit WallRateLimit(double max_rate_hz)
      : period_(max_rate_hz > 0.0 ? std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>(1.0 / max_rate_hz))
                                  : std::chrono::steady_clock::duration::zero()) {}
  /// True when the stream may publish now (and counts it).
  bool Due() {
    if (period_ == std::chrono::steady_clock::duration::zero()) return true;
    const auto now = std::chrono::steady_clock::now();
    if (now < next_) return false;
    next_ = now + period_;
    return true;
  }

 private:
  std::chrono::steady_clock::duration period_;
  std::chrono::steady_clock::time_point next_{};
};

}  // namespace rotors_sim
