#include "rotors_core/physics/link.h"

#include "rotors_core/physics/model.h"

#include "physics/ode_convert.h"
#include "physics/ode_handles.h"
#include "physics/pose_math.h"

namespace rotors_sim {
namespace physics {

using ode_convert::Vec;

Link::Link(std::string name, Model* model, const Inertial& inertial)
    : name_(std::move(name)), model_(model), inertial_(inertial) {}

void Link::AttachToBody(BodyHandle* body, const Pose3d& X_BL, bool welded) {
  body_ = body;
  X_BL_ = X_BL;
  welded_ = welded;
  pose_valid_ = false;
}

Pose3d Link::WorldPose() const {
  if (!body_) return X_WL_static_;
  if (!pose_valid_) {
    X_WL_cache_ = Compose(ode_convert::BodyPose(Ode(body_)), X_BL_);
    pose_valid_ = true;
  }
  return X_WL_cache_;
}

Pose3d Link::WorldCoGPose() const {
  const Pose3d X_WL = WorldPose();
  return {X_WL.Pos() + Rotate(X_WL.Rot(), ode_convert::FromEigen(inertial_.CoG())), X_WL.Rot()};
}

namespace {
// v_P = v_B + omega x (p_P - p_B) for a point P on the body
Vector3d PointVelocity(dBodyID body, const Vector3d& p_W) {
  dVector3 v;
  dBodyGetPointVel(body, p_W.X(), p_W.Y(), p_W.Z(), v);
  return Vec(v);
}
}  // namespace

Vector3d Link::WorldLinearVel() const { return body_ ? PointVelocity(Ode(body_), WorldPose().Pos()) : Vector3d::Zero; }

Vector3d Link::WorldCoGLinearVel() const {
  return body_ ? PointVelocity(Ode(body_), WorldCoGPose().Pos()) : Vector3d::Zero;
}

Vector3d Link::RelativeLinearVel() const { return RotateReverse(WorldPose().Rot(), WorldLinearVel()); }

Vector3d Link::WorldAngularVel() const {
  if (!body_) return Vector3d::Zero;
  const Vector3d omega_B_W = Vec(dBodyGetAngularVel(Ode(body_)));
  if (omega_rel_L_ == Vector3d::Zero) return omega_B_W;
  return omega_B_W + Rotate(WorldPose().Rot(), omega_rel_L_);
}

Vector3d Link::RelativeAngularVel() const { return RotateReverse(WorldPose().Rot(), WorldAngularVel()); }

// a = (v_k - v_{k-1}) / dt of the link origin, from the body's state before the step (kept by the
// model): includes contact and joint constraint forces, as an IMU feels them. Computed when asked
// (an IMU asks for one link; differencing every link every step cost a quarter of a step).
Vector3d Link::WorldLinearAccel() const {
  const Model::BodyStateBefore* before = body_ ? model_->StateBeforeStep(body_) : nullptr;
  if (!before) return Vector3d::Zero;
  // the link origin's velocity before the step: v_B + omega x R_WB r_B, with the body's state then
  const Vector3d r_B = X_BL_.Pos();
  const Vector3d v_before = before->v_W + before->omega_W.Cross(Rotate(before->q_WB, r_B));
  return (WorldLinearVel() - v_before) / before->dt_s;
}
Vector3d Link::RelativeLinearAccel() const { return RotateReverse(WorldPose().Rot(), WorldLinearAccel()); }
Vector3d Link::WorldAngularAccel() const {  ///< of the body it rides on
  const Model::BodyStateBefore* before = body_ ? model_->StateBeforeStep(body_) : nullptr;
  if (!before) return Vector3d::Zero;
  return (Vec(dBodyGetAngularVel(Ode(body_))) - before->omega_W) / before->dt_s;
}
Vector3d Link::RelativeAngularAccel() const { return RotateReverse(WorldPose().Rot(), WorldAngularAccel()); }

void Link::AddForce(const Vector3d& force_W) { AddForceAtWorldPosition(force_W, WorldCoGPose().Pos()); }

void Link::AddRelativeForce(const Vector3d& force_L) { AddForce(Rotate(WorldPose().Rot(), force_L)); }

void Link::AddForceAtWorldPosition(const Vector3d& force_W, const Vector3d& p_W) {
  if (!body_) return;
  dBodyAddForceAtPos(Ode(body_), force_W.X(), force_W.Y(), force_W.Z(), p_W.X(), p_W.Y(), p_W.Z());
}

void Link::AddForceAtRelativePosition(const Vector3d& force_W, const Vector3d& p_L) {
  const Pose3d X_WL = WorldPose();
  AddForceAtWorldPosition(force_W, X_WL.Pos() + Rotate(X_WL.Rot(), p_L));
}

void Link::AddTorque(const Vector3d& torque_W) {
  if (!body_) return;
  dBodyAddTorque(Ode(body_), torque_W.X(), torque_W.Y(), torque_W.Z());
}

void Link::AddRelativeTorque(const Vector3d& torque_L) { AddTorque(Rotate(WorldPose().Rot(), torque_L)); }

void Link::SetWorldAngularVel(const Vector3d& omega_W) {
  if (!body_) return;
  dBodySetAngularVel(Ode(body_), omega_W.X(), omega_W.Y(), omega_W.Z());
}

double Link::BodyMass() const {
  if (!body_) return 0.0;
  dMass m;
  dBodyGetMass(Ode(body_), &m);
  return m.mass;
}

}  // namespace physics
}  // namespace rotors_sim
