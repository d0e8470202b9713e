// Constants of the mav_comm API (mav_comm's mav_msgs/include/mav_msgs/default_values.h): Zurich's latitude and height
// and the normal gravity there.
#pragma once

#include "mav_msgs/common.h"

namespace mav_msgs {

const double kZurichLatitude = 0.8267;                                       // [rad]
const double kZurichHeight = 405.94;                                         // [m]
const double kGravity = MagnitudeOfGravity(kZurichHeight, kZurichLatitude);  // [m/s^2], about 9.8066

}  // namespace mav_msgs
