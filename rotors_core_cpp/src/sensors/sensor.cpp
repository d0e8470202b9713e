#include "rotors_core/sensors/sensor.h"

#include "rotors_core/physics/link.h"
#include "physics/pose_math.h"

namespace rotors_sim {
namespace sensors {

Sensor::Sensor(std::string name, std::string type, physics::LinkPtr parent, const physics::Pose3d& pose_in_link,
               double update_rate_hz)
    : name_(std::move(name)),
      type_(std::move(type)),
      parent_(std::move(parent)),
      X_LS_(pose_in_link),
      update_rate_hz_(update_rate_hz) {}

std::string Sensor::ParentName() const { return parent_->GetName(); }

physics::Pose3d Sensor::WorldPose() const { return Compose(parent_->WorldPose(), X_LS_); }

void Sensor::Update(const common::Time& sim_time) {
  OnStep(sim_time);
  const double t = sim_time.Double();
  if (has_updated_ && update_rate_hz_ > 0.0 && t < next_due_s_ - 1e-9) return;
  // The next update is due one period after this one was due (not after it happened), so that
  // the mean rate is update_rate even when the period is not a whole number of steps.
  const double period = update_rate_hz_ > 0.0 ? 1.0 / update_rate_hz_ : 0.0;
  next_due_s_ = (has_updated_ && t < next_due_s_ + period) ? next_due_s_ + period : t + period;
  last_update_ = sim_time;
  has_updated_ = true;
  OnUpdate(sim_time);
  updated_();
}

}  // namespace sensors
}  // namespace rotors_sim
