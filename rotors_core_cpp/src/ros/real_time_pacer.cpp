#include "rotors_core/ros/real_time_pacer.h"

#include <thread>

namespace rotors_sim {

void RealTimePacer::Restart(const common::Time& sim_time) {
  sim_start_ = sim_time;
  wall_start_ = std::chrono::steady_clock::now();
}

void RealTimePacer::WaitUntilDue(const common::Time& sim_time) {
  if (rtf_ <= 0.0) return;
  // wall_due = wall_start + (t_sim - t_sim_start) / rtf
  const double wall_offset_s = (sim_time - sim_start_).Double() / rtf_;
  const auto due = wall_start_ + std::chrono::nanoseconds(static_cast<int64_t>(wall_offset_s * 1e9));
  const auto now = std::chrono::steady_clock::now();
  if (due > now) {
    std::this_thread::sleep_until(due);
  } else if (now - due > std::chrono::seconds(1)) {
    Restart(sim_time);  // fell behind by more than a second: do not sprint to catch up
  }
}

}  // namespace rotors_sim
