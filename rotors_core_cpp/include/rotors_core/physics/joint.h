// A joint between two links (gazebo::physics::Joint): revolute/continuous hinges and prismatic
// sliders are solver joints; fixed and zero-range joints weld the child to the parent body.
#pragma once

#include <string>

#include "rotors_core/physics/physics_types.h"
#include "rotors_core/physics/solver_handles.h"

namespace rotors_sim {
namespace physics {

class Joint {
 public:
  enum class Type { kRevolute, kPrismatic, kWelded };

  Joint(std::string name, Type type, LinkPtr parent, LinkPtr child);
  ~Joint();

  const std::string& GetName() const { return name_; }
  Type GetType() const { return type_; }
  LinkPtr GetParent() const { return parent_; }
  LinkPtr GetChild() const { return child_; }

  /// Axis in the world frame (index 0 only).
  Vector3d GlobalAxis(unsigned int index) const;
  /// Axis in the child link frame.
  Vector3d LocalAxis(unsigned int index) const {
    (void)index;
    return axis_C_;
  }
  /// Joint position [rad or m] (hinge angle wrapped to (-pi, pi]).
  double Position(unsigned int index = 0) const;
  /// Joint rate of the child relative to the parent [rad/s or m/s].
  double GetVelocity(unsigned int index) const;
  /// Sets the child's velocity so that the joint rate is `velocity` now (as Gazebo's
  /// Joint::SetVelocity), keeping the parent's motion.
  void SetVelocity(unsigned int index, double velocity);
  /// Adds a joint torque/force for the coming step [N m or N].
  void SetForce(unsigned int index, double effort);

  // --- Engine side ---
  void CreateSolverJoint(SolverWorldHandle* world, const Vector3d& anchor_W, const Vector3d& axis_W, double lower,
                         double upper);

 private:
  std::string name_;
  Type type_;
  LinkPtr parent_, child_;
  Vector3d axis_C_{0, 0, 1};
  JointHandle* joint_ = nullptr;
};

}  // namespace physics
}  // namespace rotors_sim
