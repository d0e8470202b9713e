// A rigid link (gazebo::physics::Link). Links joined by fixed or zero-range joints are welded:
// they ride on the rigid body of their parent and add their mass to it, but keep their own name,
// frame, pose, velocity, acceleration and force application point.
#pragma once

#include <string>
#include <vector>

#include "rotors_core/physics/inertial.h"
#include "rotors_core/physics/physics_types.h"
#include "rotors_core/physics/solver_handles.h"

namespace rotors_sim {
namespace physics {

class Link {
 public:
  /// body == nullptr: a static link fixed at X_WL.
  Link(std::string name, Model* model, const Inertial& inertial);

  const std::string& GetName() const { return name_; }
  Model* GetModel() const { return model_; }
  const Inertial& GetInertial() const { return inertial_; }
  bool IsStatic() const { return body_ == nullptr; }
  bool IsWelded() const { return welded_; }

  // --- State (all accessors are of the link frame origin, as in Gazebo) ---
  Pose3d WorldPose() const;
  Pose3d WorldCoGPose() const;
  Vector3d WorldLinearVel() const;        ///< [m/s] link origin, world frame
  Vector3d WorldCoGLinearVel() const;     ///< [m/s] link CoG, world frame
  Vector3d RelativeLinearVel() const;     ///< [m/s] link origin, link frame
  Vector3d WorldAngularVel() const;       ///< [rad/s] world frame
  Vector3d RelativeAngularVel() const;    ///< [rad/s] link frame
  Vector3d WorldLinearAccel() const;      ///< [m/s^2] link origin, world frame (over the last step)
  Vector3d RelativeLinearAccel() const;   ///< [m/s^2] link origin, link frame
  Vector3d WorldAngularAccel() const;     ///< [rad/s^2] world frame, of the body the link rides on
  Vector3d RelativeAngularAccel() const;  ///< [rad/s^2] link frame

  // --- Forces for the coming step (ignored on static links) ---
  void AddForce(const Vector3d& force_W);          ///< [N] at the link CoG
  void AddRelativeForce(const Vector3d& force_L);  ///< [N] at the link CoG, link frame
  void AddForceAtWorldPosition(const Vector3d& force_W, const Vector3d& p_W);
  void AddForceAtRelativePosition(const Vector3d& force_W, const Vector3d& p_L);
  void AddTorque(const Vector3d& torque_W);          ///< [N m] world frame
  void AddRelativeTorque(const Vector3d& torque_L);  ///< [N m] link frame

  // --- State changes (the rigid body the link rides on; ignored on static links) ---
  void SetWorldAngularVel(const Vector3d& omega_W);  ///< [rad/s] world frame
  /// [kg] mass of the rigid body the link rides on: its own and that of the links welded to it.
  double BodyMass() const;
  /// The rigid body the link rides on (nullptr if static); welded links share their parent's.
  BodyHandle* Body() const { return body_; }

  const std::vector<JointPtr>& GetParentJoints() const { return parent_joints_; }
  const std::vector<JointPtr>& GetChildJoints() const { return child_joints_; }

  // --- Engine side ---
  /// Attach to a rigid body; X_BL is the link frame in the body frame.
  void AttachToBody(BodyHandle* body, const Pose3d& X_BL, bool welded);
  void SetStaticPose(const Pose3d& X_WL) { X_WL_static_ = X_WL; }
  /// A link on a kinematic joint moves on its body: new X_BL and its angular velocity relative to
  /// the body [rad/s, link frame].
  void MoveOnBody(const Pose3d& X_BL, const Vector3d& omega_rel_L) {
    X_BL_ = X_BL;
    omega_rel_L_ = omega_rel_L;
    pose_valid_ = false;
  }
  const Pose3d& PoseInBody() const { return X_BL_; }
  void AddParentJoint(const JointPtr& j) { parent_joints_.push_back(j); }
  void AddChildJoint(const JointPtr& j) { child_joints_.push_back(j); }
  void ClearJoints() {
    parent_joints_.clear();
    child_joints_.clear();
  }
  /// The body moved (a step, a reset): the cached world pose is stale.
  void InvalidatePose() { pose_valid_ = false; }

 private:
  std::string name_;
  Model* model_;
  Inertial inertial_;
  BodyHandle* body_ = nullptr;
  Pose3d X_BL_;         ///< link frame in the body frame
  Pose3d X_WL_static_;  ///< pose of a static link
  bool welded_ = false;
  // WorldPose() is asked for several times per step by the engine and the plugins; it is
  // computed once after each change of the body's pose.
  mutable Pose3d X_WL_cache_;
  mutable bool pose_valid_ = false;
  Vector3d omega_rel_L_ = Vector3d::Zero;  ///< angular velocity relative to the body (kinematic joint)
  std::vector<JointPtr> parent_joints_, child_joints_;
};

}  // namespace physics
}  // namespace rotors_sim
