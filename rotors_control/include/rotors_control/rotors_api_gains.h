// The attitude gains both of RotorS' controller classes default to (the Firefly's), defined once so
// that lee_position_controller.h and roll_pitch_yawrate_thrust_controller.h go in one file together.
#pragma once

#include <Eigen/Core>

namespace rotors_control {

static const Eigen::Vector3d kDefaultAttitudeGain = Eigen::Vector3d(3, 3, 0.035);
static const Eigen::Vector3d kDefaultAngularRateGain = Eigen::Vector3d(0.52, 0.52, 0.025);

}  // namespace rotors_control
