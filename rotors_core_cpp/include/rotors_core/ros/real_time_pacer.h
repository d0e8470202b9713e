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

}  // namespace rotors_sim
