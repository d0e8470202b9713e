// RotorS' fixed-wing dynamics (rotors_fixed_wing_and_more.md section 1), engine-free: the aerodynamic
// forces and moments of a fixed wing from the airspeed, the body rates, the control surface
// deflections and the throttle, with the coefficients of RotorS' yaml files (Taylor coefficients
// [n0, n1, ...]; as in RotorS, element 0 is used only in c_drag_alpha, c_lift_alpha and
// c_pitch_moment_alpha). The aerodynamics are written in FRD (x forward, y right, z down); the
// interface takes and returns FLU (the engine's body frame).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace rotors_gazebo_plugins {

/// A control surface: its channel in the normalized actuator command and its deflection range.
struct ControlSurface {
  int channel = 0;
  double deflection_min_rad = -0.349066, deflection_max_rad = 0.349066;
  /// delta = (max + min) / 2 + (max - min) / 2 * normalized (RotorS: no clamping)
  double Deflection(double normalized) const {
    return (deflection_max_rad + deflection_min_rad) / 2.0 +
           (deflection_max_rad - deflection_min_rad) / 2.0 * normalized;
  }
};

/// techpod.yaml: geometry, thrust direction, actuator channels.
struct FixedWingVehicleParams {
  double wing_span_m = 2.59, wing_surface_m2 = 0.47, chord_length_m = 0.18, thrust_inclination_rad = 0.0;
  int throttle_channel = 5;
  ControlSurface aileron_left{4}, aileron_right{0}, elevator{1}, flap{2}, rudder{3};
  /// Reads RotorS' vehicle yaml; throws std::runtime_error naming the file and the key.
  static FixedWingVehicleParams FromYaml(const std::string& path);
};

/// aero_params_<vehicle>.yaml: the aerodynamic coefficients.
struct FixedWingAeroParams {
  double alpha_max_rad = 0.27, alpha_min_rad = -0.27;
  std::vector<double> c_drag_alpha, c_drag_beta, c_drag_delta_ail, c_drag_delta_flp, c_side_force_beta, c_lift_alpha,
      c_lift_delta_ail, c_lift_delta_flp, c_roll_moment_beta, c_roll_moment_p, c_roll_moment_r, c_roll_moment_delta_ail,
      c_roll_moment_delta_flp, c_pitch_moment_alpha, c_pitch_moment_q, c_pitch_moment_delta_elv, c_yaw_moment_beta,
      c_yaw_moment_r, c_yaw_moment_delta_rud, c_thrust;
  /// Reads RotorS' aerodynamic yaml; throws std::runtime_error naming the file and the key, or a
  /// list that is too short.
  static FixedWingAeroParams FromYaml(const std::string& path);
  std::string Validate() const;  ///< "" or the first list that is too short
};

/// Surface deflections [rad] and throttle [0, 1].
struct FixedWingInputs {
  double aileron_left_rad = 0.0, aileron_right_rad = 0.0, elevator_rad = 0.0, flap_rad = 0.0, rudder_rad = 0.0;
  double throttle = 0.0;
  /// From RotorS' normalized actuator command (mav_msgs/Actuators.normalized), by channel; "" or why not.
  static std::string FromNormalized(const std::vector<double>& normalized, const FixedWingVehicleParams& vehicle,
                                    FixedWingInputs* out);
};

struct FixedWingWrench {
  Eigen::Vector3d force_B;   ///< [N] at the CoG, body frame FLU (aerodynamics plus thrust)
  Eigen::Vector3d moment_B;  ///< [N m], body frame FLU
  double airspeed_m_s = 0.0, alpha_rad = 0.0, beta_rad = 0.0;  ///< V; alpha clamped as used
  double lift_coefficient = 0.0, drag_coefficient = 0.0;
};

class FixedWingModel {
 public:
  static constexpr double kMinAirspeed_m_s = 0.1;  ///< below it alpha, beta and the rate terms are 0

  FixedWingModel(FixedWingAeroParams aero, FixedWingVehicleParams vehicle);
  /// v_air_B: airspeed vector (link velocity minus wind) in the body frame FLU [m/s]; omega_B: body
  /// rates FLU [rad/s]; rho: the air's density [kg/m^3] (StandardAtmosphereDensity at the altitude;
  /// RotorS' plugin has a constant 1.18, the standard atmosphere's at 380 m).
  FixedWingWrench Compute(const Eigen::Vector3d& v_air_B, const Eigen::Vector3d& omega_B, const FixedWingInputs& u,
                          double air_density_kg_m3) const;
  const FixedWingAeroParams& Aero() const { return aero_; }
  const FixedWingVehicleParams& Vehicle() const { return vehicle_; }

 private:
  FixedWingAeroParams aero_;
  FixedWingVehicleParams vehicle_;
};

}  // namespace rotors_gazebo_plugins
