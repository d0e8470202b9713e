#include "rotors_control/rotors_api_conversions.h"

namespace rotors_control {

MultirotorParameters MultirotorFromRotorS(const VehicleParameters& vehicle) {
  MultirotorParameters m;
  m.mass_kg = vehicle.mass_;
  m.gravity_m_s2 = vehicle.gravity_;
  m.inertia_kg_m2 = vehicle.inertia_;
  for (const Rotor& r : vehicle.rotor_configuration_.rotors) {
    RotorGeometry g;
    g.angle_rad = r.angle;
    g.arm_length_m = r.arm_length;
    g.rotor_force_constant = r.rotor_force_constant;
    g.rotor_moment_constant = r.rotor_moment_constant;
    g.direction = r.direction;
    m.rotors.push_back(g);
  }
  return m;
}

VehicleState VehicleStateFromRotorS(const EigenOdometry& odometry) {
  VehicleState s;
  s.position_W = odometry.position;
  s.orientation_W_B = odometry.orientation;
  s.velocity_B = odometry.velocity;
  s.angular_velocity_B = odometry.angular_velocity;
  return s;
}

}  // namespace rotors_control
