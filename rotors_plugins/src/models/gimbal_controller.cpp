#include "rotors_gazebo_plugins/models/gimbal_controller.h"

#include <algorithm>
#include <cmath>

namespace rotors_gazebo_plugins {

std::string GimbalParams::Validate() const {
  for (const auto& [axis, p] :
       {std::make_pair("yaw", &yaw), std::make_pair("roll", &roll), std::make_pair("pitch", &pitch)}) {
    const std::string why = p->Validate();
    if (!why.empty()) return std::string(axis) + "_pid: " + why;
  }
  return {};
}

Eigen::Vector3d GimbalController::EulerZXY(const Eigen::Matrix3d& R) {
  // R = R_z(psi) R_x(phi) R_y(theta):  R_21 = sin phi,  R_20 = -cos phi sin theta,  R_22 = cos phi cos theta,
  // R_01 = -sin psi cos phi,  R_11 = cos psi cos phi
  const double phi = std::asin(std::clamp(R(2, 1), -1.0, 1.0));
  return {std::atan2(-R(0, 1), R(1, 1)), phi, std::atan2(-R(2, 0), R(2, 2))};
}

Eigen::Vector3d GimbalController::Torques(const Eigen::Matrix3d& R_WC, const Eigen::Vector3d& command_ypr,
                                          double dt_s) {
  const Eigen::Vector3d ypr = EulerZXY(R_WC);
  return {yaw_.Torque(ypr.x(), command_ypr.x(), dt_s), roll_.Torque(ypr.y(), command_ypr.y(), dt_s),
          pitch_.Torque(ypr.z(), command_ypr.z(), dt_s)};
}

}  // namespace rotors_gazebo_plugins
