// The World Magnetic Model (NOAA NCEI's WMM, a degree-12 spherical harmonic model of the main field),
// engine-free: the field's north, east and down components at a geodetic position and date.
//
//   geocentric:  r, phi' from the WGS84 latitude phi and height h
//   V = a sum_n (a/r)^(n+1) sum_m (g_nm(t) cos m lambda + h_nm(t) sin m lambda) P_nm(sin phi')
//   g_nm(t) = g_nm + (t - t_0) gdot_nm (and h alike), P_nm Schmidt semi-normalized
//   X' = -dV/(r dphi'),  Y' = -dV/(r cos phi' dlambda),  Z' = dV/dr
//   X = X' cos(phi' - phi) - Z' sin(phi' - phi),  Y = Y',  Z = X' sin(phi' - phi) + Z' cos(phi' - phi)
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace rotors_gazebo_plugins {

class WorldMagneticModel {
 public:
  /// Reads a WMM coefficient file (NCEI's .COF format); SimError naming the file and the line.
  static WorldMagneticModel FromFile(const std::string& path);

  /// The field [T] north, east, down at latitude, longitude [deg] and height above the WGS84
  /// ellipsoid [m], at a decimal year (clamped to the model's five years of validity).
  Eigen::Vector3d FieldNed_T(double latitude_deg, double longitude_deg, double height_m, double decimal_year) const;

  double Epoch() const { return epoch_; }

 private:
  static constexpr int kDegree = 12;
  double epoch_ = 0.0;
  // [n][m], nT and nT/year
  std::vector<std::vector<double>> g_, h_, g_dot_, h_dot_;
};

/// The decimal year of a time since the Unix epoch [s] (for the model's date).
double DecimalYear(double unix_time_s);

}  // namespace rotors_gazebo_plugins
