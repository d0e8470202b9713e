// Builds a Model in a World from URDF (with <gazebo> extensions) or SDF text, through libsdformat,
// and loads its plugins. Either the whole model comes up or nothing is left in the world.
#pragma once

#include <string>
#include <vector>

#include <sdf/Model.hh>

#include "rotors_core/physics/physics_types.h"

namespace rotors_sim {

struct SpawnRequest {
  std::string xml;         ///< URDF or SDF text
  std::string model_name;  ///< empty: the name in the description
  physics::Pose3d X_WM;    ///< spawn pose of the model frame in the world
  /// Off (the default): a sensor that cannot be built (a bad camera, a missing texture) fails the
  /// whole model. On (rotors_sim_server --skip-broken-sensors): the model loads without that
  /// sensor and its plugins, and the reason is printed in one line.
  bool skip_broken_sensors = false;
};

class ModelBuilder {
 public:
  /// Throws SimError with one line naming the model and the problem.
  static physics::ModelPtr Spawn(const physics::WorldPtr& world, const SpawnRequest& request);
  /// Builds an already parsed SDF model (used for the models of a world file).
  /// `static_from_parent`: static because an enclosing model is.
  static physics::ModelPtr Build(const physics::WorldPtr& world, const sdf::Model& sdf_model, const std::string& name,
                                 const physics::Pose3d& X_WM, bool skip_broken_sensors = false,
                                 bool static_from_parent = false);
  /// A model and its nested models (<include> inside <model>), each nested one a model of its own
  /// named "parent::child" (static when an enclosing model is); a model of nested models only
  /// is not built itself. Joints into nested models are refused.
  static std::vector<physics::ModelPtr> BuildTree(const physics::WorldPtr& world, const sdf::Model& sdf_model,
                                                  const std::string& name, const physics::Pose3d& X_WM,
                                                  bool skip_broken_sensors = false, bool static_from_parent = false);
};

}  // namespace rotors_sim
