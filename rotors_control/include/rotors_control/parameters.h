// RotorS' rotors_control API (RotorS' include/rotors_control/parameters.h): the vehicle description its controllers
// take, with the AscTec Firefly as the default. Same names, fields and units as RotorS, so a controller node written
// against RotorS' library builds here unchanged. Our own controllers use vehicle_parameters.h (MultirotorParameters);
// rotors_api_conversions.h maps one to the other.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace rotors_control {

// The AscTec Firefly: six rotors at 60 degree spacing, the first at 30 degrees [rad].
static constexpr double kDefaultRotor0Angle = 0.52359877559;
static constexpr double kDefaultRotor1Angle = 1.57079632679;
static constexpr double kDefaultRotor2Angle = 2.61799387799;
static constexpr double kDefaultRotor3Angle = -2.61799387799;
static constexpr double kDefaultRotor4Angle = -1.57079632679;
static constexpr double kDefaultRotor5Angle = -0.52359877559;

static constexpr double kDefaultMass = 1.56779;                   // [kg]
static constexpr double kDefaultArmLength = 0.215;                // [m]
static constexpr double kDefaultInertiaXx = 0.0347563;            // [kg m^2]
static constexpr double kDefaultInertiaYy = 0.0458929;            // [kg m^2]
static constexpr double kDefaultInertiaZz = 0.0977;               // [kg m^2]
static constexpr double kDefaultRotorForceConstant = 8.54858e-6;  // k_F [N/(rad/s)^2]
static constexpr double kDefaultRotorMomentConstant = 1.6e-2;     // k_M [m]
static constexpr double kDefaultGravity = 9.81;                   // [m/s^2]

/// One rotor: where it sits (angle from body +x about +z, arm length), its constants and its turning
/// direction (1 counter-clockwise, -1 clockwise, seen from above).
struct Rotor {
  Rotor() = default;
  Rotor(double _angle, double _arm_length, double _rotor_force_constant, double _rotor_moment_constant, int _direction)
      : angle(_angle),
        arm_length(_arm_length),
        rotor_force_constant(_rotor_force_constant),
        rotor_moment_constant(_rotor_moment_constant),
        direction(_direction) {}
  double angle = 0.0;                                          // [rad]
  double arm_length = kDefaultArmLength;                       // [m]
  double rotor_force_constant = kDefaultRotorForceConstant;    // [N/(rad/s)^2]
  double rotor_moment_constant = kDefaultRotorMomentConstant;  // [m]
  int direction = 1;
};

/// The rotors in motor order; by default the Firefly's (directions alternate, starting ccw).
struct RotorConfiguration {
  RotorConfiguration() {
    const double angles[] = {kDefaultRotor0Angle, kDefaultRotor1Angle, kDefaultRotor2Angle,
                             kDefaultRotor3Angle, kDefaultRotor4Angle, kDefaultRotor5Angle};
    int direction = 1;
    for (double angle : angles) {
      rotors.emplace_back(angle, kDefaultArmLength, kDefaultRotorForceConstant, kDefaultRotorMomentConstant, direction);
      direction = -direction;
    }
  }
  std::vector<Rotor> rotors;
};

/// Mass [kg], gravity [m/s^2] (fixed at 9.81), inertia [kg m^2] and rotors of the vehicle.
class VehicleParameters {
 public:
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW
  VehicleParameters()
      : mass_(kDefaultMass),
        gravity_(kDefaultGravity),
        inertia_(Eigen::Vector3d(kDefaultInertiaXx, kDefaultInertiaYy, kDefaultInertiaZz).asDiagonal()) {}
  double mass_;
  const double gravity_;
  Eigen::Matrix3d inertia_;
  RotorConfiguration rotor_configuration_;
};

}  // namespace rotors_control
