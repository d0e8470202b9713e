// The world: rigid-body dynamics (ODE inside) and contacts, models, world plugins, sim time and the update events
// (gazebo::physics::World). It knows nothing about ROS or multirotors.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rotors_core/common.h"
#include "rotors_core/event.h"
#include "rotors_core/geometry/visual.h"
#include "rotors_core/physics/physics_types.h"
#include "rotors_core/physics/solver_handles.h"

struct dxThreadingImplementation;  // ODE's, kept out of this header as the other solver handles

namespace rotors_sim {
class WorldPlugin;
namespace raycast {
class RayScene;
}
namespace physics {

/// Physics settings of a world (SDF <physics>, ODE solver block).
struct PhysicsParams {
  double max_step_size_s = 0.001;  ///< [s] fixed physics step
  double real_time_factor = 1.0;   ///< pacing target; 0 = as fast as possible
  double real_time_update_rate_hz = 1000.0;
  Vector3d gravity_W{0.0, 0.0, -9.8};  ///< [m/s^2]
  bool quick_solver = true;            ///< ODE "quick" (iterative) vs "world" (direct) stepper
  int quick_iterations = 50;
  double sor = 1.3;
  double cfm = 0.0;
  double erp = 0.2;
  double contact_max_correcting_vel_m_s = 100.0;
  double contact_surface_layer_m = 0.001;
  std::string Validate() const;  ///< empty when valid, else a one-line reason
};

/// Where the world origin is on the Earth (SDF <spherical_coordinates>).
struct SphericalCoordinates {
  double latitude_deg = 0.0, longitude_deg = 0.0, elevation_m = 0.0, heading_deg = 0.0;
};

/// One contact point found in the last step (between two links, or a link and static geometry).
struct Contact {
  std::string collision1, collision2;  ///< "model::link::collision"
  Link* link1 = nullptr;               ///< nullptr for static geometry
  Link* link2 = nullptr;
  Vector3d position_W, normal_W;
  double depth_m = 0.0;
  Vector3d force1_W, torque1_W;  ///< wrench on link1 from the contact, world frame
  Vector3d force2_W, torque2_W;
};

/// How many messages (solver warnings such as "LCP internal error") ODE has reported in this process.
uint64_t OdeMessageCount();

class World : public std::enable_shared_from_this<World> {
 public:
  static WorldPtr Create(const std::string& name, const PhysicsParams& params);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const std::string& Name() const { return name_; }
  const PhysicsParams& Physics() const { return params_; }
  /// Throw SimError (the world unchanged) when the new value fails PhysicsParams::Validate().
  void SetRealTimeFactor(double rtf);
  /// The physics step [s]; set it before spawning models with plugins (they read it when they load).
  void SetMaxStepSize(double step_s);
  Vector3d Gravity() const { return params_.gravity_W; }
  const SphericalCoordinates& Origin() const { return origin_; }
  void SetOrigin(const SphericalCoordinates& origin) { origin_ = origin; }
  const geometry::Lighting& GetLighting() const { return lighting_; }
  void SetLighting(const geometry::Lighting& lighting) { lighting_ = lighting; }
  common::Time SimTime() const { return sim_time_; }
  uint64_t Iterations() const { return iterations_; }

  ModelPtr ModelByName(const std::string& name) const;
  const std::vector<ModelPtr>& Models() const { return models_; }
  size_t ModelCount() const { return models_.size(); }
  /// Changes whenever a model is added or removed (a new model may reuse a removed one's address).
  uint64_t ModelSetVersion() const { return model_set_version_; }
  /// Removes a model and its plugins; false if there is none of that name.
  bool RemoveModel(const std::string& name);

  /// Advances the world by `steps` physics steps (update-begin event, collide, integrate,
  /// update-end event each).
  void Step(unsigned int steps = 1);
  /// reset_world: models back to their spawn poses, velocities zero, plugins Reset(); time kept.
  void ResetWorld();
  /// reset_simulation: as ResetWorld and the sim time back to zero.
  void ResetSimulation();

  /// Paused or running, with the reason given by whoever paused it (a user, lockstep); fires the
  /// pause event on every change. The world does not step itself: whoever calls Step() honours it.
  void SetPaused(bool paused, const std::string& reason = "");
  bool IsPaused() const { return paused_; }
  const std::string& PauseReason() const { return pause_reason_; }
  /// Steps after which the host did not wait for a participant it steps in turns with (ROS lockstep):
  /// a run with such steps depends on wall-clock timing. Reported by the host, read by plugins (the bag).
  void SetUnwaitedSteps(uint64_t steps, const std::string& first_reason) {
    unwaited_steps_ = steps;
    first_unwaited_reason_ = first_reason;
  }
  uint64_t UnwaitedSteps() const { return unwaited_steps_; }
  const std::string& FirstUnwaitedReason() const { return first_unwaited_reason_; }

  const std::vector<Contact>& Contacts() const { return contacts_; }
  /// Fires the stop event once, then unloads world plugins and removes every model (plugins hold
  /// shared pointers to their world and model; call this before dropping the last WorldPtr).
  void Fini();
  event::WorldEvents& Events() { return events_; }
  /// The world's visuals as a ray-casting scene (made at the first call), for laser sensors.
  raycast::RayScene& Rays();

  // --- Engine side (used by builders) ---
  SolverWorldHandle* SolverWorld() const { return solver_world_; }
  SpaceHandle* Space() const { return space_; }
  void AddModel(const ModelPtr& model);
  void AddPlugin(std::unique_ptr<WorldPlugin> plugin);
  /// State the plugins of this world share, by key (e.g. rotors_gazebo_plugins' vehicle buses): it
  /// lives and dies with the world, so two worlds in one process never share it. The engine does
  /// not look inside; the key's owner decides the type.
  std::shared_ptr<void>& PluginState(const std::string& key) { return plugin_state_[key]; }

 private:
  World(std::string name, const PhysicsParams& params);
  friend struct WorldCollision;  // the solver's near callback (world.cpp)
  void Collide();
  void CollectContacts();

  std::string name_;
  PhysicsParams params_;
  SphericalCoordinates origin_;
  geometry::Lighting lighting_;
  SolverWorldHandle* solver_world_ = nullptr;
  /// This world's state of ODE's one process-wide random generator, which the quick stepper draws
  /// from to reorder constraint rows (dRandInt); 0, ODE's own start, at creation and at a reset
  unsigned long quick_step_random_state_ = 0;
  dxThreadingImplementation* threading_ = nullptr;  ///< this world's own ODE stepping threading
  SpaceHandle* space_ = nullptr;
  ContactGroupHandle* contact_group_ = nullptr;
  std::vector<ModelPtr> models_;
  uint64_t model_set_version_ = 0;
  std::vector<std::unique_ptr<WorldPlugin>> plugins_;
  common::Time sim_time_;
  uint64_t iterations_ = 0;
  bool paused_ = false;
  uint64_t unwaited_steps_ = 0;
  std::string first_unwaited_reason_;
  bool stopped_ = false;
  std::string pause_reason_;
  event::WorldEvents events_;
  std::vector<Contact> contacts_;
  struct PendingContacts;  // this step's contacts with the solver's force feedback (world.cpp)
  std::unique_ptr<PendingContacts> pending_;
  common::Time wall_start_;
  std::unique_ptr<raycast::RayScene> rays_;
  std::map<std::string, std::shared_ptr<void>> plugin_state_;
};

}  // namespace physics
}  // namespace rotors_sim
