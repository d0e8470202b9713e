#include "rotors_core/physics/joint.h"

#include "rotors_core/physics/link.h"

#include <cmath>

#include "rotors_core/physics/model.h"
#include "rotors_core/physics/spin_moment.h"
#include "physics/ode_convert.h"
#include "physics/ode_handles.h"
#include "physics/pose_math.h"

namespace rotors_sim {
namespace physics {

Joint::Joint(std::string name, Type type, LinkPtr parent, LinkPtr child)
    : name_(std::move(name)), type_(type), parent_(std::move(parent)), child_(std::move(child)) {}

Joint::~Joint() {
  if (joint_) dJointDestroy(Ode(joint_));
}

void Joint::CreateSolverJoint(SolverWorldHandle* world, const Vector3d& anchor_W, const Vector3d& axis_W, double lower,
                              double upper) {
  axis_C_ = child_->WorldPose().Rot().RotateVectorReverse(axis_W);
  lower_ = lower;
  upper_ = upper;
  if (type_ == Type::kWelded) return;
  dBodyID child_body = Ode(child_->Body());
  dBodyID parent_body = parent_ ? Ode(parent_->Body()) : nullptr;
  if (type_ == Type::kRevolute) {
    joint_ = Handle(dJointCreateHinge(Ode(world), nullptr));
    dJointAttach(Ode(joint_), child_body, parent_body);
    dJointSetHingeAnchor(Ode(joint_), anchor_W.X(), anchor_W.Y(), anchor_W.Z());
    dJointSetHingeAxis(Ode(joint_), axis_W.X(), axis_W.Y(), axis_W.Z());
    if (lower > -1e15) dJointSetHingeParam(Ode(joint_), dParamLoStop, lower);
    if (upper < 1e15) dJointSetHingeParam(Ode(joint_), dParamHiStop, upper);
  } else {
    joint_ = Handle(dJointCreateSlider(Ode(world), nullptr));
    dJointAttach(Ode(joint_), child_body, parent_body);
    dJointSetSliderAxis(Ode(joint_), axis_W.X(), axis_W.Y(), axis_W.Z());
    if (lower > -1e15) dJointSetSliderParam(Ode(joint_), dParamLoStop, lower);
    if (upper < 1e15) dJointSetSliderParam(Ode(joint_), dParamHiStop, upper);
  }
}

Vector3d Joint::GlobalAxis(unsigned int /*index*/) const { return Rotate(child_->WorldPose().Rot(), axis_C_); }

double Joint::Position(unsigned int /*index*/) const {
  if (type_ == Type::kKinematic) return q_;
  if (!joint_) return 0.0;
  return type_ == Type::kRevolute ? dJointGetHingeAngle(Ode(joint_)) : dJointGetSliderPosition(Ode(joint_));
}

double Joint::GetVelocity(unsigned int /*index*/) const {
  if (type_ == Type::kKinematic) return qdot_;
  if (!joint_) return 0.0;
  return type_ == Type::kRevolute ? dJointGetHingeAngleRate(Ode(joint_)) : dJointGetSliderPositionRate(Ode(joint_));
}

void Joint::SetVelocity(unsigned int /*index*/, double velocity) {
  if (type_ == Type::kKinematic) {
    qdot_ = velocity;
    return;
  }
  if (!joint_) return;
  dBodyID child = Ode(child_->Body());
  const Vector3d axis_W = GlobalAxis(0);
  const Vector3d omega_parent_W = parent_ ? parent_->WorldAngularVel() : Vector3d::Zero;
  const Vector3d p_child_W = ode_convert::Vec(dBodyGetPosition(child));
  // v of the child's CoG as if rigidly attached to the parent
  Vector3d v_child_W = Vector3d::Zero;
  if (parent_ && parent_->Body()) {
    dVector3 v;
    dBodyGetPointVel(Ode(parent_->Body()), p_child_W.X(), p_child_W.Y(), p_child_W.Z(), v);
    v_child_W = ode_convert::Vec(v);
  }
  if (type_ == Type::kRevolute) {
    // omega_child = omega_parent + qdot * axis
    const Vector3d omega_W = omega_parent_W + axis_W * velocity;
    dBodySetAngularVel(child, omega_W.X(), omega_W.Y(), omega_W.Z());
    // the child's CoG may be off the axis: v += qdot * axis x (p - anchor)
    dVector3 anchor;
    dJointGetHingeAnchor(Ode(joint_), anchor);
    v_child_W += (axis_W * velocity).Cross(p_child_W - ode_convert::Vec(anchor));
  } else {
    dBodySetAngularVel(child, omega_parent_W.X(), omega_parent_W.Y(), omega_parent_W.Z());
    v_child_W += axis_W * velocity;
  }
  dBodySetLinearVel(child, v_child_W.X(), v_child_W.Y(), v_child_W.Z());
}

void Joint::SetForce(unsigned int /*index*/, double effort) {
  if (!joint_) return;  // kinematic: a torque between two links of one body does not move it
  if (type_ == Type::kRevolute) {
    dJointAddHingeTorque(Ode(joint_), effort);
  } else {
    dJointAddSliderForce(Ode(joint_), effort);
  }
}

void Joint::MakeKinematic(const Pose3d& X_PC0, const Vector3d& axis_C, double spin_inertia) {
  X_PC0_ = X_PC0;
  axis_C_ = axis_C.Normalized();
  spin_inertia_ = spin_inertia;
  ResetKinematic();
}

void Joint::ResetKinematic() {
  if (type_ != Type::kKinematic) return;
  q_ = qdot_ = qdot_applied_ = 0.0;
  PlaceChild();
}

void Joint::ApplySpinMoment(double dt_s) {
  if (spin_inertia_ > 0.0 && dt_s > 0.0) {
    const Vector3d a_W = GlobalAxis(0), omega_W = parent_->WorldAngularVel();
    const double axis_W[3] = {a_W.X(), a_W.Y(), a_W.Z()}, w_W[3] = {omega_W.X(), omega_W.Y(), omega_W.Z()};
    double M_W[3];
    SpinMoment(axis_W, spin_inertia_, qdot_, qdot_applied_, 1.0 / dt_s, w_W, M_W);
    parent_->AddTorque(Vector3d(M_W[0], M_W[1], M_W[2]));
  }
  qdot_applied_ = qdot_;
}

void Joint::AdvanceKinematic(double dt_s) {
  // q in (-pi, pi], as a hinge angle (one turn at most per step: |qdot dt| < pi)
  q_ += qdot_ * dt_s;
  if (q_ > M_PI || q_ <= -M_PI) q_ = std::remainder(q_, 2.0 * M_PI);
  PlaceChild();
}

void Joint::FindTurningGeoms() {
  Model* model = child_->GetModel();
  turning_geoms_.clear();
  geoms_seen_ = model ? model->Geoms().size() : 0;
  if (!model) return;
  constexpr double kTolerance = 1e-9;
  for (const auto& g : model->Geoms()) {
    if (g.second->link != child_.get()) continue;
    const Pose3d& X_LG = g.second->X_LG;
    // R(a, q) X_LG = X_LG (up to the shape's own symmetry) when the geom's centre lies on the axis and
    // the shape is a sphere, or a cylinder or capsule whose own axis (z) is the joint's
    const bool centre_on_axis = X_LG.Pos().Cross(axis_C_).Length() < kTolerance;
    const int shape = dGeomGetClass(Ode(g.first));
    const bool round_about_z = shape == dCylinderClass || shape == dCapsuleClass;
    const bool symmetric =
        centre_on_axis &&
        (shape == dSphereClass ||
         (round_about_z && X_LG.Rot().RotateVectorReverse(axis_C_).Cross(Vector3d::UnitZ).Length() < kTolerance));
    if (!symmetric) turning_geoms_.push_back({g.first, X_LG});
  }
}

void Joint::PlaceChild() {
  // X_BC = X_BP X_PC0 R(a, q): the child turns about its own origin (the joint frame)
  const Pose3d X_PC = Compose(X_PC0_, Pose3d(Vector3d::Zero, ignition::math::Quaterniond(axis_C_, q_)));
  const Pose3d X_BC = Compose(parent_->PoseInBody(), X_PC);
  child_->MoveOnBody(X_BC, axis_C_ * qdot_);
  Model* model = child_->GetModel();
  if (!model) return;
  const bool place_all = model->Geoms().size() != geoms_seen_;  // new geoms: every one placed once
  if (place_all) FindTurningGeoms();
  auto place = [&X_BC](GeomHandle* geom, const Pose3d& X_LG) {
    const Pose3d X_BG = Compose(X_BC, X_LG);
    dGeomSetOffsetPosition(Ode(geom), X_BG.Pos().X(), X_BG.Pos().Y(), X_BG.Pos().Z());
    dQuaternion q;
    ode_convert::ToOde(X_BG.Rot(), q);
    dGeomSetOffsetQuaternion(Ode(geom), q);
  };
  if (place_all) {
    for (const auto& g : model->Geoms())
      if (g.second->link == child_.get()) place(g.first, g.second->X_LG);
  } else {
    for (const auto& [geom, X_LG] : turning_geoms_) place(geom, X_LG);
  }
}

}  // namespace physics
}  // namespace rotors_sim
