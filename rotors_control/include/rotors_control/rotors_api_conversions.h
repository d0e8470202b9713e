// RotorS' parameter types (parameters.h, common.h) to our controller library's (vehicle_parameters.h,
// lee_controller.h): what the RotorS API classes hand to our control laws.
#pragma once

#include "rotors_control/common.h"
#include "rotors_control/lee_controller.h"
#include "rotors_control/parameters.h"
#include "rotors_control/vehicle_parameters.h"

namespace rotors_control {

MultirotorParameters MultirotorFromRotorS(const VehicleParameters& vehicle);
VehicleState VehicleStateFromRotorS(const EigenOdometry& odometry);

}  // namespace rotors_control
