// The one place where the simulator's frames meet the autopilots': ours are ENU world and FLU body
// (REP-103), PX4's, ArduPilot's and Betaflight's attitude input NED world and FRD body.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rotors_gazebo_plugins {
namespace frames {

/// v_NED = (north, east, down) of v_ENU = (east, north, up)
inline Eigen::Vector3d NedFromEnu(const Eigen::Vector3d& v_ENU) { return {v_ENU.y(), v_ENU.x(), -v_ENU.z()}; }
/// v_FRD = (forward, right, down) of v_FLU = (forward, left, up)
inline Eigen::Vector3d FrdFromFlu(const Eigen::Vector3d& v_FLU) { return {v_FLU.x(), -v_FLU.y(), -v_FLU.z()}; }

/// q_NED_FRD = q_NED_ENU q_ENU_FLU q_FLU_FRD (both outer rotations are half turns)
inline Eigen::Quaterniond NedFrdFromEnuFlu(const Eigen::Quaterniond& q_ENU_FLU) {
  const double s = std::sqrt(0.5);
  const Eigen::Quaterniond q_NED_ENU(0.0, s, s, 0.0);      // the half turn about (1, 1, 0)/sqrt(2)
  const Eigen::Quaterniond q_FLU_FRD(0.0, 1.0, 0.0, 0.0);  // the half turn about x
  Eigen::Quaterniond q = q_NED_ENU * q_ENU_FLU * q_FLU_FRD;
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  return q.normalized();
}

}  // namespace frames
}  // namespace rotors_gazebo_plugins
