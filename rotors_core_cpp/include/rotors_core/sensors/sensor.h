// A sensor declared in a link's SDF (<gazebo reference="link"><sensor ...>) (gazebo::sensors::Sensor).
// The engine drives it at its <update_rate> and fires Updated; what it measures is the job of its
// plugins, or of a subclass (CameraSensor renders).
#pragma once

#include <memory>
#include <string>

#include "rotors_core/common.h"
#include "rotors_core/event.h"
#include "rotors_core/physics/physics_types.h"

namespace rotors_sim {
namespace sensors {

class Sensor {
 public:
  virtual ~Sensor() = default;
  Sensor(std::string name, std::string type, physics::LinkPtr parent, const physics::Pose3d& pose_in_link,
         double update_rate_hz);

  const std::string& Name() const { return name_; }
  const std::string& Type() const { return type_; }
  std::string ParentName() const;
  physics::LinkPtr ParentLink() const { return parent_; }
  const physics::Pose3d& Pose() const { return X_LS_; }  ///< in the parent link frame
  physics::Pose3d WorldPose() const;
  double UpdateRate() const { return update_rate_hz_; }  ///< [Hz]; 0: every step
  common::Time LastUpdateTime() const { return last_update_; }
  event::ConnectionPtr ConnectUpdated(std::function<void()> cb) { return updated_.Connect(std::move(cb)); }

  /// Engine side, every step: OnStep, then, when an update is due (every 1/rate of sim time on
  /// average), OnUpdate and Updated.
  void Update(const common::Time& sim_time);
  void Reset() {
    last_update_ = common::Time();
    has_updated_ = false;
    next_due_s_ = 0.0;
    OnReset();
  }

 protected:
  /// Called at every physics step, before the update (if one is due).
  virtual void OnStep(const common::Time& /*sim_time*/) {}
  /// Called at each update, before Updated fires.
  virtual void OnUpdate(const common::Time& /*sim_time*/) {}
  /// Called by Reset().
  virtual void OnReset() {}

 private:
  std::string name_, type_;
  physics::LinkPtr parent_;
  physics::Pose3d X_LS_;
  double update_rate_hz_;
  common::Time last_update_;
  bool has_updated_ = false;
  double next_due_s_ = 0.0;  ///< [s] sim time the next update is due
  event::EventT<> updated_;
};
using SensorPtr = std::shared_ptr<Sensor>;

}  // namespace sensors
}  // namespace rotors_sim
