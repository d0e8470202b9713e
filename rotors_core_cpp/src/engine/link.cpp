#include "rotors_core/physics/link.h"

#include "ode_convert.h"
#include "ode_handles.h"
#include "pose_math.h"

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
  return {X_WL.Pos() + X_WL.Rot().RotateVector(ode_convert::FromEigen(inertial_.CoG())), X_WL.Rot()};
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

Vector3d Link::RelativeLinearVel() const { return WorldPose().Rot().RotateVectorReverse(WorldLinearVel()); }

Vector3d Link::WorldAngularVel() const {
  if (!body_) return Vector3d::Zero;
  const Vector3d omega_B_W = Vec(dBodyGetAngularVel(Ode(body_)));
  if (omega_rel_L_ == Vector3d::Zero) return omega_B_W;
  return omega_B_W + WorldPose().Rot().RotateVector(omega_rel_L_);
}

Vector3d Link::RelativeAngularVel() const { return WorldPose().Rot().RotateVectorReverse(WorldAngularVel()); }

Vector3d Link::WorldLinearAccel() const { return a_W_; }
Vector3d Link::RelativeLinearAccel() const { return WorldPose().Rot().RotateVectorReverse(a_W_); }
Vector3d Link::WorldAngularAccel() const { return alpha_W_; }
Vector3d Link::RelativeAngularAccel() const { return WorldPose().Rot().RotateVectorReverse(alpha_W_); }

void Link::AddForce(const Vector3d& force_W) { AddForceAtWorldPosition(force_W, WorldCoGPose().Pos()); }

void Link::AddRelativeForce(const Vector3d& force_L) { AddForce(WorldPose().Rot().RotateVector(force_L)); }

void Link::AddForceAtWorldPosition(const Vector3d& force_W, const Vector3d& p_W) {
  if (!body_) return;
  dBodyAddForceAtPos(Ode(body_), force_W.X(), force_W.Y(), force_W.Z(), p_W.X(), p_W.Y(), p_W.Z());
}

void Link::AddForceAtRelativePosition(const Vector3d& force_W, const Vector3d& p_L) {
  const Pose3d X_WL = WorldPose();
  AddForceAtWorldPosition(force_W, X_WL.Pos() + X_WL.Rot().RotateVector(p_L));
}

void Link::AddTorque(const Vector3d& torque_W) {
  if (!body_) return;
  dBodyAddTorque(Ode(body_), torque_W.X(), torque_W.Y(), torque_W.Z());
}

void Link::AddRelativeTorque(const Vector3d& torque_L) { AddTorque(WorldPose().Rot().RotateVector(torque_L)); }

void Link::RecordVelocityBeforeStep() {
  v_W_prev_ = WorldLinearVel();
  omega_W_prev_ = WorldAngularVel();
}

void Link::UpdateAccelerationAfterStep(double dt_s) {
  if (!body_ || dt_s <= 0.0) return;
  // a = (v_k - v_{k-1}) / dt : includes contact and joint constraint forces, as an IMU feels them
  a_W_ = (WorldLinearVel() - v_W_prev_) / dt_s;
  alpha_W_ = (WorldAngularVel() - omega_W_prev_) / dt_s;
}

void Link::ClearAcceleration() {
  a_W_ = Vector3d::Zero;
  alpha_W_ = Vector3d::Zero;
}

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
