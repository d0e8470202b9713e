// Conversions between ODE arrays and ignition-math / Eigen types (engine internal).
#pragma once

#include <Eigen/Core>
#include <ignition/math/Pose3.hh>
#include <ode/ode.h>

namespace rotors_sim {
namespace ode_convert {

inline ignition::math::Vector3d Vec(const dReal* v) { return {v[0], v[1], v[2]}; }

inline ignition::math::Quaterniond Quat(const dReal* q) { return {q[0], q[1], q[2], q[3]}; }

inline void ToOde(const ignition::math::Quaterniond& q, dQuaternion out) {
  out[0] = q.W();
  out[1] = q.X();
  out[2] = q.Y();
  out[3] = q.Z();
}

inline ignition::math::Pose3d BodyPose(dBodyID body) {
  return {Vec(dBodyGetPosition(body)), Quat(dBodyGetQuaternion(body))};
}

inline void SetBodyPose(dBodyID body, const ignition::math::Pose3d& X_WB) {
  dBodySetPosition(body, X_WB.Pos().X(), X_WB.Pos().Y(), X_WB.Pos().Z());
  dQuaternion q;
  ToOde(X_WB.Rot(), q);
  dBodySetQuaternion(body, q);
}

/// Places a geom that is on no body (a static model's collision).
inline void SetGeomPose(dGeomID geom, const ignition::math::Pose3d& X_WG) {
  dGeomSetPosition(geom, X_WG.Pos().X(), X_WG.Pos().Y(), X_WG.Pos().Z());
  dQuaternion q;
  ToOde(X_WG.Rot(), q);
  dGeomSetQuaternion(geom, q);
}

inline Eigen::Vector3d ToEigen(const ignition::math::Vector3d& v) { return {v.X(), v.Y(), v.Z()}; }
inline ignition::math::Vector3d FromEigen(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Matrix3d ToEigen(const ignition::math::Quaterniond& q) {
  const ignition::math::Matrix3d m(q);
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m(i, j);
  return r;
}

}  // namespace ode_convert
}  // namespace rotors_sim
