#include "rotors_gazebo_plugins/models/fixed_wing_model.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <yaml-cpp/yaml.h>

namespace rotors_gazebo_plugins {
namespace {

YAML::Node LoadYaml(const std::string& path) {
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error("fixed-wing parameters '" + path + "': " + e.what());
  }
}

template <typename T>
T Get(const YAML::Node& node, const std::string& key, const std::string& path) {
  if (!node[key]) throw std::runtime_error("fixed-wing parameters '" + path + "': missing key '" + key + "'");
  try {
    return node[key].as<T>();
  } catch (const YAML::Exception&) {
    throw std::runtime_error("fixed-wing parameters '" + path + "': key '" + key + "' has the wrong type");
  }
}

ControlSurface Surface(const YAML::Node& root, const std::string& key, const std::string& path) {
  const YAML::Node node = root[key];
  if (!node) throw std::runtime_error("fixed-wing parameters '" + path + "': missing key '" + key + "'");
  ControlSurface s;
  s.channel = Get<int>(node, "channel", path + ":" + key);
  s.deflection_min_rad = Get<double>(node, "deflection_min", path + ":" + key);
  s.deflection_max_rad = Get<double>(node, "deflection_max", path + ":" + key);
  return s;
}

/// sum_k c[k] x^k
double Taylor(const std::vector<double>& c, double x) {
  double sum = 0.0, power = 1.0;
  for (double ck : c) {
    sum += ck * power;
    power *= x;
  }
  return sum;
}

}  // namespace

FixedWingVehicleParams FixedWingVehicleParams::FromYaml(const std::string& path) {
  const YAML::Node root = LoadYaml(path);
  FixedWingVehicleParams p;
  p.wing_span_m = Get<double>(root, "wing_span", path);
  p.wing_surface_m2 = Get<double>(root, "wing_surface", path);
  p.chord_length_m = Get<double>(root, "chord_length", path);
  p.thrust_inclination_rad = Get<double>(root, "thrust_inclination", path);
  p.throttle_channel = Get<int>(root, "throttle_channel", path);
  p.aileron_left = Surface(root, "aileron_left", path);
  p.aileron_right = Surface(root, "aileron_right", path);
  p.elevator = Surface(root, "elevator", path);
  p.flap = Surface(root, "flap", path);
  p.rudder = Surface(root, "rudder", path);
  return p;
}

FixedWingAeroParams FixedWingAeroParams::FromYaml(const std::string& path) {
  const YAML::Node root = LoadYaml(path);
  FixedWingAeroParams p;
  p.alpha_max_rad = Get<double>(root, "alpha_max", path);
  p.alpha_min_rad = Get<double>(root, "alpha_min", path);
  const std::pair<const char*, std::vector<double>*> lists[] = {
      {"c_drag_alpha", &p.c_drag_alpha},
      {"c_drag_beta", &p.c_drag_beta},
      {"c_drag_delta_ail", &p.c_drag_delta_ail},
      {"c_drag_delta_flp", &p.c_drag_delta_flp},
      {"c_side_force_beta", &p.c_side_force_beta},
      {"c_lift_alpha", &p.c_lift_alpha},
      {"c_lift_delta_ail", &p.c_lift_delta_ail},
      {"c_lift_delta_flp", &p.c_lift_delta_flp},
      {"c_roll_moment_beta", &p.c_roll_moment_beta},
      {"c_roll_moment_p", &p.c_roll_moment_p},
      {"c_roll_moment_r", &p.c_roll_moment_r},
      {"c_roll_moment_delta_ail", &p.c_roll_moment_delta_ail},
      {"c_roll_moment_delta_flp", &p.c_roll_moment_delta_flp},
      {"c_pitch_moment_alpha", &p.c_pitch_moment_alpha},
      {"c_pitch_moment_q", &p.c_pitch_moment_q},
      {"c_pitch_moment_delta_elv", &p.c_pitch_moment_delta_elv},
      {"c_yaw_moment_beta", &p.c_yaw_moment_beta},
      {"c_yaw_moment_r", &p.c_yaw_moment_r},
      {"c_yaw_moment_delta_rud", &p.c_yaw_moment_delta_rud},
      {"c_thrust", &p.c_thrust}};
  for (const auto& list : lists) *list.second = Get<std::vector<double>>(root, list.first, path);
  const std::string why = p.Validate();
  if (!why.empty()) throw std::runtime_error("fixed-wing parameters '" + path + "': " + why);
  return p;
}

std::string FixedWingAeroParams::Validate() const {
  // the terms the model uses: [0..2] for drag in alpha, [1..2] for beta and the surfaces, [1] for the rest
  const std::pair<const char*, const std::vector<double>*> need[] = {{"c_drag_alpha", &c_drag_alpha},
                                                                     {"c_drag_beta", &c_drag_beta},
                                                                     {"c_drag_delta_ail", &c_drag_delta_ail},
                                                                     {"c_drag_delta_flp", &c_drag_delta_flp}};
  for (const auto& n : need)
    if (n.second->size() < 3)
      return std::string(n.first) + " needs 3 coefficients, has " + std::to_string(n.second->size());
  if (c_lift_alpha.size() < 4) return "c_lift_alpha needs 4 coefficients, has " + std::to_string(c_lift_alpha.size());
  if (c_thrust.size() < 3) return "c_thrust needs 3 coefficients, has " + std::to_string(c_thrust.size());
  const std::pair<const char*, const std::vector<double>*> two[] = {
      {"c_side_force_beta", &c_side_force_beta},
      {"c_lift_delta_ail", &c_lift_delta_ail},
      {"c_lift_delta_flp", &c_lift_delta_flp},
      {"c_roll_moment_beta", &c_roll_moment_beta},
      {"c_roll_moment_p", &c_roll_moment_p},
      {"c_roll_moment_r", &c_roll_moment_r},
      {"c_roll_moment_delta_ail", &c_roll_moment_delta_ail},
      {"c_roll_moment_delta_flp", &c_roll_moment_delta_flp},
      {"c_pitch_moment_alpha", &c_pitch_moment_alpha},
      {"c_pitch_moment_q", &c_pitch_moment_q},
      {"c_pitch_moment_delta_elv", &c_pitch_moment_delta_elv},
      {"c_yaw_moment_beta", &c_yaw_moment_beta},
      {"c_yaw_moment_r", &c_yaw_moment_r},
      {"c_yaw_moment_delta_rud", &c_yaw_moment_delta_rud}};
  for (const auto& n : two)
    if (n.second->size() < 2)
      return std::string(n.first) + " needs 2 coefficients, has " + std::to_string(n.second->size());
  if (!(alpha_min_rad < alpha_max_rad)) return "alpha_min must be below alpha_max";
  return {};
}

std::string FixedWingInputs::FromNormalized(const std::vector<double>& n, const FixedWingVehicleParams& v,
                                            FixedWingInputs* out) {
  for (int channel : {v.aileron_left.channel, v.aileron_right.channel, v.elevator.channel, v.flap.channel,
                      v.rudder.channel, v.throttle_channel})
    if (channel < 0 || channel >= static_cast<int>(n.size()))
      return "normalized has " + std::to_string(n.size()) + " values, channel " + std::to_string(channel) +
             " is needed";
  for (double x : n)
    if (!std::isfinite(x)) return "normalized has NaN or inf";
  // a surface's normalized value in [-1, 1] is its deflection range; the throttle is in [0, 1]
  // (RotorS clamps neither: a deflection beyond the surface's limit would silently be flown)
  constexpr double kSlack = 1e-9;
  const std::pair<const char*, const ControlSurface*> surfaces[] = {{"aileron_left", &v.aileron_left},
                                                                    {"aileron_right", &v.aileron_right},
                                                                    {"elevator", &v.elevator},
                                                                    {"flap", &v.flap},
                                                                    {"rudder", &v.rudder}};
  for (const auto& [name, surface] : surfaces) {
    const double x = n[surface->channel];
    if (std::abs(x) > 1.0 + kSlack) {
      std::ostringstream why;
      why << "normalized[" << surface->channel << "] = " << x << " puts the " << name << " at "
          << surface->Deflection(x) << " rad, outside its deflection range [" << surface->deflection_min_rad << ", "
          << surface->deflection_max_rad << "] rad (normalized values are -1 .. 1)";
      return why.str();
    }
  }
  const double t = n[v.throttle_channel];
  if (t < -kSlack || t > 1.0 + kSlack) {
    std::ostringstream why;
    why << "normalized[" << v.throttle_channel << "] = " << t << ": the throttle must be in [0, 1]";
    return why.str();
  }
  out->aileron_left_rad = v.aileron_left.Deflection(n[v.aileron_left.channel]);
  out->aileron_right_rad = v.aileron_right.Deflection(n[v.aileron_right.channel]);
  out->elevator_rad = v.elevator.Deflection(n[v.elevator.channel]);
  out->flap_rad = v.flap.Deflection(n[v.flap.channel]);
  out->rudder_rad = v.rudder.Deflection(n[v.rudder.channel]);
  out->throttle = t;
  return {};
}

FixedWingModel::FixedWingModel(FixedWingAeroParams aero, FixedWingVehicleParams vehicle)
    : aero_(std::move(aero)), vehicle_(vehicle) {
  const std::string why = aero_.Validate();
  if (!why.empty()) throw std::invalid_argument("fixed-wing aerodynamic parameters: " + why);
}

FixedWingWrench FixedWingModel::Compute(const Eigen::Vector3d& v_air_B, const Eigen::Vector3d& omega_B,
                                        const FixedWingInputs& u, double air_density_kg_m3) const {
  const FixedWingAeroParams& a = aero_;
  // FLU -> FRD (180 deg about x): (u, v, w) = (vx, -vy, -vz), (p, q, r) = (wx, -wy, -wz)
  const double uu = v_air_B.x(), vv = -v_air_B.y(), ww = -v_air_B.z();
  const double p = omega_B.x(), q = -omega_B.y(), r = -omega_B.z();
  const double V = v_air_B.norm();
  FixedWingWrench out;
  out.airspeed_m_s = V;
  // beta = asin(v / V); alpha = atan(w / u), clamped (both 0 at low speed, RotorS)
  const double beta = V > kMinAirspeed_m_s ? std::asin(vv / V) : 0.0;
  double alpha = uu > kMinAirspeed_m_s ? std::atan(ww / uu) : 0.0;
  alpha = std::min(std::max(alpha, a.alpha_min_rad), a.alpha_max_rad);
  out.alpha_rad = alpha;
  out.beta_rad = beta;
  const double b = vehicle_.wing_span_m, c = vehicle_.chord_length_m;
  // normalized rates p^ = p b / 2V, q^ = q c / 2V, r^ = r b / 2V
  const double p_hat = V > kMinAirspeed_m_s ? p * b / (2.0 * V) : 0.0;
  const double q_hat = V > kMinAirspeed_m_s ? q * c / (2.0 * V) : 0.0;
  const double r_hat = V > kMinAirspeed_m_s ? r * b / (2.0 * V) : 0.0;
  const double sum_ail = u.aileron_left_rad + u.aileron_right_rad;
  const double diff_ail = u.aileron_left_rad - u.aileron_right_rad;
  const double sum_flp = 2.0 * u.flap_rad, diff_flp = 0.0;
  // C_D = cDa[0..2](alpha) + cDb[1] beta + cDb[2] beta^2 + cDail[1] Sa + cDail[2] Sa^2 + cDflp[1] Sf + cDflp[2] Sf^2
  const double C_D = Taylor({a.c_drag_alpha[0], a.c_drag_alpha[1], a.c_drag_alpha[2]}, alpha) +
                     a.c_drag_beta[1] * beta + a.c_drag_beta[2] * beta * beta + a.c_drag_delta_ail[1] * sum_ail +
                     a.c_drag_delta_ail[2] * sum_ail * sum_ail + a.c_drag_delta_flp[1] * sum_flp +
                     a.c_drag_delta_flp[2] * sum_flp * sum_flp;
  const double C_Y = a.c_side_force_beta[1] * beta;
  // C_L = cLa[0..3](alpha) + cLail[1] Sa + cLflp[1] Sf
  const double C_L = Taylor({a.c_lift_alpha[0], a.c_lift_alpha[1], a.c_lift_alpha[2], a.c_lift_alpha[3]}, alpha) +
                     a.c_lift_delta_ail[1] * sum_ail + a.c_lift_delta_flp[1] * sum_flp;
  const double C_l = a.c_roll_moment_beta[1] * beta + a.c_roll_moment_p[1] * p_hat + a.c_roll_moment_r[1] * r_hat +
                     a.c_roll_moment_delta_ail[1] * diff_ail + a.c_roll_moment_delta_flp[1] * diff_flp;
  const double C_m = a.c_pitch_moment_alpha[0] + a.c_pitch_moment_alpha[1] * alpha + a.c_pitch_moment_q[1] * q_hat +
                     a.c_pitch_moment_delta_elv[1] * u.elevator_rad;
  const double C_n =
      a.c_yaw_moment_beta[1] * beta + a.c_yaw_moment_r[1] * r_hat + a.c_yaw_moment_delta_rud[1] * u.rudder_rad;
  out.lift_coefficient = C_L;
  out.drag_coefficient = C_D;
  // q-bar S = 1/2 rho V^2 S
  const double qS = 0.5 * air_density_kg_m3 * V * V * vehicle_.wing_surface_m2;
  const Eigen::Vector3d F_w = qS * Eigen::Vector3d(-C_D, C_Y, -C_L);
  const Eigen::Vector3d M_w = qS * Eigen::Vector3d(b * C_l, c * C_m, b * C_n);
  // body -> wind rotation (rows), applied transposed: F_FRD = R^T F_w
  const double ca = std::cos(alpha), sa = std::sin(alpha), cb = std::cos(beta), sb = std::sin(beta);
  Eigen::Matrix3d R_wind_body;
  R_wind_body << ca * cb, sb, sa * cb, -ca * sb, cb, -sa * sb, -sa, 0.0, ca;
  // thrust T = c_thrust[0..2](t) along (cos i, 0, sin i) in FRD
  const double T = Taylor({a.c_thrust[0], a.c_thrust[1], a.c_thrust[2]}, u.throttle);
  const double i = vehicle_.thrust_inclination_rad;
  const Eigen::Vector3d F_frd = R_wind_body.transpose() * F_w + T * Eigen::Vector3d(std::cos(i), 0.0, std::sin(i));
  const Eigen::Vector3d M_frd = R_wind_body.transpose() * M_w;
  out.force_B = Eigen::Vector3d(F_frd.x(), -F_frd.y(), -F_frd.z());  // FRD -> FLU
  out.moment_B = Eigen::Vector3d(M_frd.x(), -M_frd.y(), -M_frd.z());
  return out;
}

}  // namespace rotors_gazebo_plugins
