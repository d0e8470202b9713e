#include "rotors_core/physics/joint.h"

#include "rotors_core/physics/link.h"
#include "ode_convert.h"
#include "ode_handles.h"

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

Vector3d Joint::GlobalAxis(unsigned int /*index*/) const { return child_->WorldPose().Rot().RotateVector(axis_C_); }

double Joint::Position(unsigned int /*index*/) const {
  if (!joint_) return 0.0;
  return type_ == Type::kRevolute ? dJointGetHingeAngle(Ode(joint_)) : dJointGetSliderPosition(Ode(joint_));
}

double Joint::GetVelocity(unsigned int /*index*/) const {
  if (!joint_) return 0.0;
  return type_ == Type::kRevolute ? dJointGetHingeAngleRate(Ode(joint_)) : dJointGetSliderPositionRate(Ode(joint_));
}

void Joint::SetVelocity(unsigned int /*index*/, double velocity) {
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
  if (!joint_) return;
  if (type_ == Type::kRevolute) {
    dJointAddHingeTorque(Ode(joint_), effort);
  } else {
    dJointAddSliderForce(Ode(joint_), effort);
  }
}

}  // namespace physics
}  // namespace rotors_sim
