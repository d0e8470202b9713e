// Frame composition written as X_AC = X_AB * X_BC (engine internal).
#pragma once

#include <ignition/math/Pose3.hh>

namespace rotors_sim {

inline ignition::math::Pose3d Compose(const ignition::math::Pose3d& X_AB, const ignition::math::Pose3d& X_BC) {
  return {X_AB.Pos() + X_AB.Rot().RotateVector(X_BC.Pos()), X_AB.Rot() * X_BC.Rot()};
}

inline ignition::math::Pose3d Inverse(const ignition::math::Pose3d& X_AB) {
  const ignition::math::Quaterniond q_BA = X_AB.Rot().Inverse();
  return {q_BA.RotateVector(-X_AB.Pos()), q_BA};
}

}  // namespace rotors_sim
