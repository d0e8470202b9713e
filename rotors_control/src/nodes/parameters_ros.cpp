#include "rotors_control/parameters_ros.h"

#include <sstream>

namespace rotors_control {

namespace {
const char kVehicleHint[] = "load the vehicle yaml, resource/<mav>.yaml";
const char kGainHint[] = "load the controller yaml, e.g. resource/lee_controller_<mav>.yaml";
}  // namespace

std::string LoadVehicleParameters(ParameterReader& reader, VehicleParameters* v) {
  std::string why = reader.Require("mass", &v->mass_kg, kVehicleHint);
  if (!why.empty()) return why;
  v->gravity_m_s2 = VehicleParameters{}.gravity_m_s2;  // the one default, whatever *v held
  why = reader.Optional("gravity", &v->gravity_m_s2, "RotorS' value; the world's may differ, as in the book's example");
  if (!why.empty()) return why;
  const char* keys[3][3] = {{"inertia/xx", "inertia/xy", "inertia/xz"},
                            {"inertia/xy", "inertia/yy", "inertia/yz"},
                            {"inertia/xz", "inertia/yz", "inertia/zz"}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double value = 0.0;
      why = i == j ? reader.Require(keys[i][j], &value, kVehicleHint)
                   : reader.Optional(keys[i][j], &value, "a principal-axes body");
      if (!why.empty()) return why;
      v->inertia_kg_m2(i, j) = value;
    }
  v->rotors.clear();
  for (int i = 0; reader.Has("rotor_configuration/" + std::to_string(i)); ++i) {
    const std::string base = "rotor_configuration/" + std::to_string(i) + "/";
    Rotor r;
    for (const auto& field : {std::make_pair("angle", &r.angle_rad), std::make_pair("arm_length", &r.arm_length_m),
                              std::make_pair("rotor_force_constant", &r.rotor_force_constant),
                              std::make_pair("rotor_moment_constant", &r.rotor_moment_constant)}) {
      why = reader.Require(base + field.first, field.second, kVehicleHint);
      if (!why.empty()) return why;
    }
    double direction = 0.0;
    why = reader.Require(base + "direction", &direction, kVehicleHint);
    if (!why.empty()) return why;
    r.direction = static_cast<int>(std::lround(direction));
    why = reader.Optional(base + "max_rot_velocity", &r.max_rot_velocity_rad_s, "rotor speed not limited");
    if (!why.empty()) return why;
    v->rotors.push_back(r);
  }
  if (v->rotors.empty())
    return "missing parameter " + reader.Resolve("rotor_configuration") + " (" + kVehicleHint + ")";
  return v->Validate();
}

std::string LoadAttitudeGains(ParameterReader& reader, AttitudeGains* gains) {
  std::string why = reader.RequireVector("attitude_gain", &gains->attitude_gain, kGainHint);
  return why.empty() ? reader.RequireVector("angular_rate_gain", &gains->angular_rate_gain, kGainHint) : why;
}

std::string LoadLeeParameters(ParameterReader& reader, LeePositionControllerParameters* p) {
  std::string why = reader.RequireVector("position_gain", &p->position_gain, kGainHint);
  if (why.empty()) why = reader.RequireVector("velocity_gain", &p->velocity_gain, kGainHint);
  if (why.empty()) why = LoadAttitudeGains(reader, &p->attitude);
  if (why.empty()) why = LoadVehicleParameters(reader, &p->vehicle);
  if (why.empty()) why = reader.Optional("max_tilt_angle", &p->max_tilt_angle_rad, "no tilt limit");
  return why.empty() ? p->Validate() : why;
}

void ReportParameters(const ParameterReader& reader, const std::string& tag) {
  for (const std::string& line : reader.Defaults()) ROS_INFO("[%s] %s", tag.c_str(), line.c_str());
  const std::vector<std::string> unknown = reader.UnknownKeys();
  if (unknown.empty()) return;
  std::string names;
  for (const std::string& name : unknown) names += (names.empty() ? "" : ", ") + name;
  ROS_WARN("[%s] unknown parameter(s), not used: %s (a typo?)", tag.c_str(), names.c_str());
}

}  // namespace rotors_control
