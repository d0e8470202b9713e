#include "rotors_control/parameters_ros.h"

namespace rotors_control {

namespace {
std::string Require(const ros::NodeHandle& nh, const std::string& name, double* value) {
  if (!nh.getParam(name, *value)) return "missing parameter " + nh.resolveName(name) + " (load the vehicle yaml)";
  return {};
}
}  // namespace

std::string LoadVehicleParameters(const ros::NodeHandle& nh, VehicleParameters* v) {
  std::string why = Require(nh, "mass", &v->mass_kg);
  if (!why.empty()) return why;
  nh.param("gravity", v->gravity_m_s2, v->gravity_m_s2);
  const char* keys[3][3] = {{"inertia/xx", "inertia/xy", "inertia/xz"},
                            {"inertia/xy", "inertia/yy", "inertia/yz"},
                            {"inertia/xz", "inertia/yz", "inertia/zz"}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double value = 0.0;
      if (i == j) {
        why = Require(nh, keys[i][j], &value);
        if (!why.empty()) return why;
      } else {
        nh.param(keys[i][j], value, 0.0);
      }
      v->inertia_kg_m2(i, j) = value;
    }
  v->rotors.clear();
  for (int i = 0; nh.hasParam("rotor_configuration/" + std::to_string(i)); ++i) {
    const std::string base = "rotor_configuration/" + std::to_string(i) + "/";
    Rotor r;
    for (const auto& field : {std::make_pair("angle", &r.angle_rad), std::make_pair("arm_length", &r.arm_length_m),
                              std::make_pair("rotor_force_constant", &r.rotor_force_constant),
                              std::make_pair("rotor_moment_constant", &r.rotor_moment_constant)}) {
      why = Require(nh, base + field.first, field.second);
      if (!why.empty()) return why;
    }
    double direction = 0.0;
    why = Require(nh, base + "direction", &direction);
    if (!why.empty()) return why;
    r.direction = static_cast<int>(std::lround(direction));
    nh.param(base + "max_rot_velocity", r.max_rot_velocity_rad_s, 0.0);  // ours, optional
    v->rotors.push_back(r);
  }
  if (v->rotors.empty())
    return "missing parameter " + nh.resolveName("rotor_configuration") + " (load the vehicle yaml)";
  return v->Validate();
}

std::string LoadGain(const ros::NodeHandle& nh, const std::string& name, Eigen::Vector3d* gain) {
  if (!nh.hasParam(name)) return {};
  const char* axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (!nh.getParam(name + "/" + axes[i], (*gain)[i]))
      return "parameter " + nh.resolveName(name) + " needs numbers x, y and z";
  }
  return {};
}

std::string LoadAttitudeGains(const ros::NodeHandle& nh, AttitudeGains* gains) {
  std::string why = LoadGain(nh, "attitude_gain", &gains->attitude_gain);
  return why.empty() ? LoadGain(nh, "angular_rate_gain", &gains->angular_rate_gain) : why;
}

std::string LoadLeeParameters(const ros::NodeHandle& nh, LeePositionControllerParameters* p) {
  for (const std::string& why :
       {LoadGain(nh, "position_gain", &p->position_gain), LoadGain(nh, "velocity_gain", &p->velocity_gain),
        LoadAttitudeGains(nh, &p->attitude), LoadVehicleParameters(nh, &p->vehicle)})
    if (!why.empty()) return why;
  nh.param("max_tilt_angle", p->max_tilt_angle_rad, p->max_tilt_angle_rad);  // ours, optional
  return p->Validate();
}

}  // namespace rotors_control
