// Loading controller and vehicle parameters (the layout of lee_controller_<mav>.yaml and <mav>.yaml)
// through any reader with the project's parameter policy: rotors_params::RosParamReader in the
// ROS nodes, rotors_params::MapParamReader in the Python module. No ROS here.
//   mass, inertia/{xx, yy, zz} (off-diagonal terms optional, 0), rotor_configuration/<i>/{angle,
//   arm_length, rotor_force_constant, rotor_moment_constant, direction}, optional max_rot_velocity
//   and gravity (announced when absent: 9.81, RotorS' value); attitude_gain and angular_rate_gain
//   {x, y, z}; position_gain, velocity_gain and the optional max_tilt_angle. Each returns "" or the
//   reason naming the parameter.
//   The omav (omav.yaml, omav_pose_controller.yaml; ours): mass, gravity and inertia as above,
//   tilt_rotor_configuration/<i>/{x, y, z, yaw, rotor_force_constant, upper_moment_constant,
//   lower_moment_constant, upper_direction, max_rot_velocity}; the four gains {x, y, z}.
#pragma once

#include <cmath>
#include <string>

#include "rotors_control/attitude_control_law.h"
#include "rotors_control/lee_controller.h"
#include "rotors_control/tilt_rotor_controller.h"
#include "rotors_control/vehicle_parameters.h"

namespace rotors_control {

namespace parameter_hints {
constexpr char kVehicle[] = "load the vehicle yaml, resource/<mav>.yaml";
constexpr char kGain[] = "load the controller yaml, e.g. resource/lee_controller_<mav>.yaml";
}  // namespace parameter_hints

/// mass, gravity (default RotorS' 9.81, announced) and inertia/{xx, ..., yz}: what every vehicle
/// yaml holds, multirotor or tilt-rotor.
template <class Reader>
std::string LoadRigidBody(Reader& reader, double* mass_kg, double* gravity_m_s2, Eigen::Matrix3d* inertia_kg_m2) {
  std::string why = reader.Require("mass", mass_kg, parameter_hints::kVehicle);
  if (!why.empty()) return why;
  *gravity_m_s2 = MultirotorParameters{}.gravity_m_s2;  // the one default, whatever it held
  why = reader.Optional("gravity", gravity_m_s2, "RotorS' value; the world's may differ, as in the book's example");
  if (!why.empty()) return why;
  const char* keys[3][3] = {{"inertia/xx", "inertia/xy", "inertia/xz"},
                            {"inertia/xy", "inertia/yy", "inertia/yz"},
                            {"inertia/xz", "inertia/yz", "inertia/zz"}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double value = 0.0;
      why = i == j ? reader.Require(keys[i][j], &value, parameter_hints::kVehicle)
                   : reader.Optional(keys[i][j], &value, "a principal-axes body");
      if (!why.empty()) return why;
      (*inertia_kg_m2)(i, j) = value;
    }
  return {};
}

template <class Reader>
std::string LoadVehicleParameters(Reader& reader, MultirotorParameters* v) {
  std::string why = LoadRigidBody(reader, &v->mass_kg, &v->gravity_m_s2, &v->inertia_kg_m2);
  if (!why.empty()) return why;
  v->rotors.clear();
  for (int i = 0; reader.Has("rotor_configuration/" + std::to_string(i)); ++i) {
    const std::string base = "rotor_configuration/" + std::to_string(i) + "/";
    RotorGeometry r;
    for (const auto& field : {std::make_pair("angle", &r.angle_rad), std::make_pair("arm_length", &r.arm_length_m),
                              std::make_pair("rotor_force_constant", &r.rotor_force_constant),
                              std::make_pair("rotor_moment_constant", &r.rotor_moment_constant)}) {
      why = reader.Require(base + field.first, field.second, parameter_hints::kVehicle);
      if (!why.empty()) return why;
    }
    double direction = 0.0;
    why = reader.Require(base + "direction", &direction, parameter_hints::kVehicle);
    if (!why.empty()) return why;
    r.direction = static_cast<int>(std::lround(direction));
    why = reader.Optional(base + "max_rot_velocity", &r.max_rot_velocity_rad_s, "rotor speed not limited");
    if (!why.empty()) return why;
    v->rotors.push_back(r);
  }
  if (v->rotors.empty())
    return "missing parameter " + reader.Resolve("rotor_configuration") + " (" + parameter_hints::kVehicle + ")";
  return v->Validate();
}

template <class Reader>
std::string LoadAttitudeGains(Reader& reader, AttitudeGains* gains) {
  std::string why = reader.RequireVector("attitude_gain", &gains->attitude_gain, parameter_hints::kGain);
  return why.empty() ? reader.RequireVector("angular_rate_gain", &gains->angular_rate_gain, parameter_hints::kGain)
                     : why;
}

template <class Reader>
std::string LoadLeeParameters(Reader& reader, LeeControllerParameters* p) {
  std::string why = reader.RequireVector("position_gain", &p->position_gain, parameter_hints::kGain);
  if (why.empty()) why = reader.RequireVector("velocity_gain", &p->velocity_gain, parameter_hints::kGain);
  if (why.empty()) why = LoadAttitudeGains(reader, &p->attitude);
  if (why.empty()) why = LoadVehicleParameters(reader, &p->vehicle);
  if (why.empty()) why = reader.Optional("max_tilt_angle", &p->max_tilt_angle_rad, "no tilt limit");
  return why.empty() ? p->Validate() : why;
}

template <class Reader>
std::string LoadTiltRotorParameters(Reader& reader, TiltRotorControllerParameters* p) {
  std::string why = LoadRigidBody(reader, &p->mass_kg, &p->gravity_m_s2, &p->inertia_kg_m2);
  if (!why.empty()) return why;
  p->arms.clear();
  for (int i = 0; reader.Has("tilt_rotor_configuration/" + std::to_string(i)); ++i) {
    const std::string base = "tilt_rotor_configuration/" + std::to_string(i) + "/";
    TiltRotorArm arm;
    double direction = 0.0;
    for (const auto& field : {std::make_pair("x", &arm.position_B.x()), std::make_pair("y", &arm.position_B.y()),
                              std::make_pair("z", &arm.position_B.z()), std::make_pair("yaw", &arm.yaw_rad),
                              std::make_pair("rotor_force_constant", &arm.rotor_force_constant),
                              std::make_pair("upper_moment_constant", &arm.upper_moment_constant),
                              std::make_pair("lower_moment_constant", &arm.lower_moment_constant),
                              std::make_pair("upper_direction", &direction),
                              std::make_pair("max_rot_velocity", &arm.max_rot_velocity_rad_s)}) {
      why = reader.Require(base + field.first, field.second, parameter_hints::kVehicle);
      if (!why.empty()) return why;
    }
    arm.upper_direction = static_cast<int>(std::lround(direction));
    p->arms.push_back(arm);
  }
  if (p->arms.empty())
    return "missing parameter " + reader.Resolve("tilt_rotor_configuration") + " (load resource/omav.yaml)";
  for (const auto& gain :
       {std::make_pair("position_gain", &p->position_gain), std::make_pair("velocity_gain", &p->velocity_gain),
        std::make_pair("attitude_gain", &p->attitude_gain),
        std::make_pair("angular_rate_gain", &p->angular_rate_gain)}) {
    why = reader.RequireVector(gain.first, gain.second, "load resource/omav_pose_controller.yaml");
    if (!why.empty()) return why;
  }
  return p->Validate();
}

}  // namespace rotors_control
