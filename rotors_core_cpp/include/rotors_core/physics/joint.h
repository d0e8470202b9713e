// A joint between two links (gazebo::physics::Joint): revolute/continuous hinges and prismatic
// sliders are solver joints; fixed and zero-range joints weld the child to the parent body.
//
// A kinematic joint (a revolute joint the model names in <kinematic_joint>, e.g. a rotor's) is no
// solver joint: its child rides on the parent's rigid body (mass and inertia lumped at the joint's
// zero position), its rate is what SetVelocity sets and its position integrates that rate. The
// child's pose, angular velocity and collision geoms follow the joint. The child's spin momentum
// h = J_a qdot a (J_a: its inertia about the axis) is carried by the body through the moment
// M = -dh/dt = -(omega_B x h) - J_a qddot a (Euler's equation of a spinning rotor), so the body
// feels the gyroscopic coupling that a separate solver body would give, without a solver joint.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "rotors_core/physics/physics_types.h"
#include "rotors_core/physics/solver_handles.h"

namespace rotors_sim {
namespace physics {

class Joint {
 public:
  enum class Type { kRevolute, kPrismatic, kWelded, kKinematic };

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
  /// The joint's limits [rad or m] as the description gives them (+-1e16: none, Gazebo's value).
  double LowerLimit(unsigned int /*index*/ = 0) const { return lower_; }
  double UpperLimit(unsigned int /*index*/ = 0) const { return upper_; }

  bool IsKinematic() const { return type_ == Type::kKinematic; }

  // --- Engine side ---
  /// Kinematic joint: X_PC0 is the child frame in the parent link frame at q = 0 (the joint
  /// frame, as in URDF), axis_C the axis in the child frame, spin_inertia the child's inertia about
  /// the axis through its origin [kg m^2]. The child must already ride on the parent's body.
  void MakeKinematic(const Pose3d& X_PC0, const Vector3d& axis_C, double spin_inertia);
  /// Kinematic: the child's inertia about the axis through its origin, J_a [kg m^2].
  double SpinInertia() const { return spin_inertia_; }
  /// Kinematic: applies this step's spin moment to the body (before the solver step).
  void ApplySpinMoment(double dt_s);
  /// Kinematic: integrates the position over the step, moves the child and its geoms.
  void AdvanceKinematic(double dt_s);
  /// Kinematic: back to q = 0 at rest (model reset).
  void ResetKinematic();
  void CreateSolverJoint(SolverWorldHandle* world, const Vector3d& anchor_W, const Vector3d& axis_W, double lower,
                         double upper);

 private:
  std::string name_;
  Type type_;
  LinkPtr parent_, child_;
  Vector3d axis_C_{0, 0, 1};
  double lower_ = -1e16, upper_ = 1e16;
  JointHandle* joint_ = nullptr;
  // kinematic joints
  void PlaceChild();
  /// The child's geoms whose pose changes as the child turns (a rotor's disc about its own axis does
  /// not: it is placed once); found again when the model's geoms change.
  void FindTurningGeoms();
  std::vector<std::pair<GeomHandle*, Pose3d>> turning_geoms_;  ///< geom, X_LG
  size_t geoms_seen_ = static_cast<size_t>(-1);                ///< the model's geom count they were found for
  Pose3d X_PC0_;
  double spin_inertia_ = 0.0;  ///< [kg m^2] J_a
  double q_ = 0.0;             ///< [rad]
  double qdot_ = 0.0;          ///< [rad/s]
  double qdot_applied_ = 0.0;  ///< [rad/s] the rate of the last spin moment (for qddot)
};

}  // namespace physics
}  // namespace rotors_sim
