// The 1976 standard atmosphere below 11 km, the one model of air the sensors, the aerodynamics
// and the autopilot codecs share (the barometer plugin, the fixed wing's dynamic pressure, PX4's
// HIL_SENSOR and its pitot tube, Betaflight's state packet).
#pragma once

namespace rotors_gazebo_plugins {

/// Pressure [Pa] at a geometric altitude [m]: h_gp = R_e h / (R_e + h), T = T_0 - L h_gp,
/// p = p_0 (T / T_0)^(g_0 M / (R L)).
double StandardAtmospherePressure(double altitude_m);

/// Pressure altitude [m] of a pressure [Pa], as PX4 and barometers define it (geopotential, no
/// correction): h = T_0 / L (1 - (p / p_0)^(R L / (g_0 M))).
double PressureAltitude(double pressure_Pa);

/// Temperature [deg C] at a pressure altitude [m]: T_0 - L h.
double StandardAtmosphereTemperature_C(double altitude_m);

/// Air density [kg/m^3] at a geometric altitude [m]: rho = p M / (R T) with p and T as above
/// (1.2250 at sea level, 1.1673 at 500 m, RotorS' worlds' elevation).
double StandardAtmosphereDensity(double altitude_m);

}  // namespace rotors_gazebo_plugins
