#include "rotors_gazebo_plugins/models/standard_atmosphere.h"

#include <cmath>

namespace rotors_gazebo_plugins {
namespace {
constexpr double kEarthRadius_m = 6356766.0, kT0_K = 288.15, kP0_Pa = 101325.0, kLapse_K_m = 0.0065;
constexpr double kG0 = 9.80665, kMolarMass_kg_kmol = 28.9644, kGasConstant_J_kmol_K = 8314.32;
/// g_0 M / (R L)
constexpr double kExponent = kG0 * kMolarMass_kg_kmol / (kGasConstant_J_kmol_K * kLapse_K_m);
}  // namespace

double StandardAtmospherePressure(double h_m) {
  // h_gp = R_e h / (R_e + h)
  const double h_gp = kEarthRadius_m * h_m / (kEarthRadius_m + h_m);
  // T = T_0 - L h_gp
  const double T = kT0_K - kLapse_K_m * h_gp;
  // p = p_0 (T / T_0)^(g_0 M / (R L))
  return kP0_Pa * std::pow(T / kT0_K, kExponent);
}

double PressureAltitude(double pressure_Pa) {
  // h = T_0 / L (1 - (p / p_0)^(R L / (g_0 M)))
  return kT0_K / kLapse_K_m * (1.0 - std::pow(pressure_Pa / kP0_Pa, 1.0 / kExponent));
}

double StandardAtmosphereTemperature_C(double altitude_m) { return kT0_K - kLapse_K_m * altitude_m - 273.15; }

double StandardAtmosphereDensity(double h_m) {
  const double h_gp = kEarthRadius_m * h_m / (kEarthRadius_m + h_m);
  const double T = kT0_K - kLapse_K_m * h_gp;
  // rho = p M / (R T)
  return StandardAtmospherePressure(h_m) * kMolarMass_kg_kmol / (kGasConstant_J_kmol_K * T);
}

}  // namespace rotors_gazebo_plugins
