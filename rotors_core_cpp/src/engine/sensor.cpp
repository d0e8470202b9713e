#include "rotors_core/sensors/sensor.h"

#include "rotors_core/physics/link.h"
#include "pose_math.h"

namespace rotors_sim {
namespace sensors {

Sensor::Sensor(std::string name, std::string type, physics::LinkPtr parent, const physics::Pose3d& pose_in_link,
               double update_rate_hz)
    : name_(std::move(name)), type_(std::move(type)), parent_(std::move(parent)), X_LS_(pose_in_link),
      update_rate_hz_(update_rate_hz) {}

std::string Sensor::ParentName() const { return parent_->GetName(); }

physics::Pose3d Sensor::WorldPose() const { return Compose(parent_->WorldPose(), X_LS_); }

void Sensor::Update(const common::Time& sim_time) {
  if (has_updated_ && update_rate_hz_ > 0.0 &&
      (sim_time - last_update_).Double() < 1.0 / update_rate_hz_ - 1e-9)
    return;
  last_update_ = sim_time;
  has_updated_ = true;
  OnUpdate(sim_time);
  updated_();
}

}  // namespace sensors
}  // namespace rotors_sim
