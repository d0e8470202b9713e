// Frame composition written as X_AC = X_AB * X_BC (engine internal).
#pragma once

#include <Eigen/Geometry>
#include <ignition/math/Pose3.hh>

namespace rotors_sim {

/// R(q) v for a unit quaternion q = (w, u): v + w t + u x t with t = 2 u x v. ignition's
/// RotateVector forms two quaternion products and an inverse (about three times the work), and
/// poses are composed and vectors rotated dozens of times per step.
inline ignition::math::Vector3d Rotate(const ignition::math::Quaterniond& q, const ignition::math::Vector3d& v) {
  const double w = q.W(), ux = q.X(), uy = q.Y(), uz = q.Z();
  const double tx = 2.0 * (uy * v.Z() - uz * v.Y());
  const double ty = 2.0 * (uz * v.X() - ux * v.Z());
  const double tz = 2.0 * (ux * v.Y() - uy * v.X());
  return {v.X() + w * tx + (uy * tz - uz * ty), v.Y() + w * ty + (uz * tx - ux * tz),
          v.Z() + w * tz + (ux * ty - uy * tx)};
}

/// R(q)^T v for a unit quaternion.
inline ignition::math::Vector3d RotateReverse(const ignition::math::Quaterniond& q, const ignition::math::Vector3d& v) {
  return Rotate(ignition::math::Quaterniond(q.W(), -q.X(), -q.Y(), -q.Z()), v);
}

inline ignition::math::Pose3d Compose(const ignition::math::Pose3d& X_AB, const ignition::math::Pose3d& X_BC) {
  return {X_AB.Pos() + Rotate(X_AB.Rot(), X_BC.Pos()), X_AB.Rot() * X_BC.Rot()};
}

inline ignition::math::Pose3d Inverse(const ignition::math::Pose3d& X_AB) {
  const ignition::math::Quaterniond q_BA = X_AB.Rot().Inverse();
  return {q_BA.RotateVector(-X_AB.Pos()), q_BA};
}

/// The pose as an Eigen isometry (for code that works in Eigen: the renderer, the ray caster).
inline Eigen::Isometry3d ToIsometry(const ignition::math::Pose3d& X) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(X.Rot().W(), X.Rot().X(), X.Rot().Y(), X.Rot().Z()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(X.Pos().X(), X.Pos().Y(), X.Pos().Z());
  return T;
}

}  // namespace rotors_sim
