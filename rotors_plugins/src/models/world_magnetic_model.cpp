#include "rotors_gazebo_plugins/models/world_magnetic_model.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>

#include "rotors_core/error.h"

namespace rotors_gazebo_plugins {
namespace {
constexpr double kWgs84A_km = 6378.137, kWgs84F = 1.0 / 298.257223563;
constexpr double kReferenceRadius_km = 6371.2;  // the model's geomagnetic reference radius a

double Factorial(int n) {
  double f = 1.0;
  for (int i = 2; i <= n; ++i) f *= i;
  return f;
}
}  // namespace

WorldMagneticModel WorldMagneticModel::FromFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw rotors_sim::SimError("worldMagneticModel: cannot read '" + path + "' (a WMM .COF file)");
  WorldMagneticModel model;
  const auto zeros = std::vector<std::vector<double>>(kDegree + 1, std::vector<double>(kDegree + 1, 0.0));
  model.g_ = model.h_ = model.g_dot_ = model.h_dot_ = zeros;
  std::string line;
  if (!std::getline(in, line) || !(std::istringstream(line) >> model.epoch_))
    throw rotors_sim::SimError("worldMagneticModel '" + path + "': the first line must begin with the epoch (2025.0)");
  int count = 0, line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.rfind("9999", 0) == 0) break;
    std::istringstream fields(line);
    int n, m;
    double g, h, g_dot, h_dot;
    if (!(fields >> n >> m >> g >> h >> g_dot >> h_dot) || n < 1 || n > kDegree || m < 0 || m > n)
      throw rotors_sim::SimError("worldMagneticModel '" + path + "' line " + std::to_string(line_number) +
                                 ": not 'n m g h gdot hdot' with 1 <= n <= 12, 0 <= m <= n");
    model.g_[n][m] = g;
    model.h_[n][m] = h;
    model.g_dot_[n][m] = g_dot;
    model.h_dot_[n][m] = h_dot;
    ++count;
  }
  if (count != kDegree * (kDegree + 3) / 2)
    throw rotors_sim::SimError("worldMagneticModel '" + path + "': " + std::to_string(count) +
                               " coefficients, a degree-12 model has 90");
  return model;
}

Eigen::Vector3d WorldMagneticModel::FieldNed_T(double latitude_deg, double longitude_deg, double height_m,
                                               double decimal_year) const {
  const double t = std::clamp(decimal_year, epoch_, epoch_ + 5.0) - epoch_;
  const double phi = latitude_deg * M_PI / 180.0, lambda = longitude_deg * M_PI / 180.0, h_km = height_m * 1e-3;
  // geodetic -> geocentric spherical
  const double e2 = kWgs84F * (2.0 - kWgs84F);
  const double rc = kWgs84A_km / std::sqrt(1.0 - e2 * std::sin(phi) * std::sin(phi));
  const double p = (rc + h_km) * std::cos(phi), z = (rc * (1.0 - e2) + h_km) * std::sin(phi);
  const double r = std::hypot(p, z), phi_c = std::asin(z / r);
  // unnormalized associated Legendre functions of cos(theta) = sin(phi'), theta the colatitude, and
  // their theta derivatives (no Condon-Shortley phase), then Schmidt semi-normalized
  const double cos_t = std::sin(phi_c), sin_t = std::max(std::cos(phi_c), 1e-12);
  double P[kDegree + 1][kDegree + 1] = {}, dP[kDegree + 1][kDegree + 1] = {};
  P[0][0] = 1.0;
  for (int m = 1; m <= kDegree; ++m) P[m][m] = (2 * m - 1) * sin_t * P[m - 1][m - 1];
  for (int m = 0; m < kDegree; ++m) P[m + 1][m] = (2 * m + 1) * cos_t * P[m][m];
  for (int m = 0; m <= kDegree; ++m)
    for (int n = m + 2; n <= kDegree; ++n)
      P[n][m] = ((2 * n - 1) * cos_t * P[n - 1][m] - (n + m - 1) * P[n - 2][m]) / (n - m);
  for (int n = 1; n <= kDegree; ++n)
    for (int m = 0; m <= n; ++m) {
      // dP_n^m / dtheta = (n cos(theta) P_n^m - (n + m) P_(n-1)^m) / sin(theta)
      dP[n][m] = (n * cos_t * P[n][m] - (n + m) * (m <= n - 1 ? P[n - 1][m] : 0.0)) / sin_t;
    }
  double x = 0.0, y = 0.0, zc = 0.0;  // geocentric north, east, down [nT]
  for (int n = 1; n <= kDegree; ++n) {
    const double ratio = std::pow(kReferenceRadius_km / r, n + 2);
    for (int m = 0; m <= n; ++m) {
      const double schmidt = m == 0 ? 1.0 : std::sqrt(2.0 * Factorial(n - m) / Factorial(n + m));
      const double g = g_[n][m] + t * g_dot_[n][m], h = h_[n][m] + t * h_dot_[n][m];
      const double c = std::cos(m * lambda), s = std::sin(m * lambda);
      // X' = -dV/(r dphi') = dV/(r dtheta); Y' = -dV/(r cos phi' dlambda); Z' = dV/dr
      x += ratio * (g * c + h * s) * schmidt * dP[n][m];
      y += ratio * m * (g * s - h * c) * schmidt * P[n][m] / sin_t;
      zc -= ratio * (n + 1) * (g * c + h * s) * schmidt * P[n][m];
    }
  }
  // geocentric -> geodetic north and down
  const double d = phi_c - phi;
  const Eigen::Vector3d ned_nT(x * std::cos(d) - zc * std::sin(d), y, x * std::sin(d) + zc * std::cos(d));
  return ned_nT * 1e-9;
}

double DecimalYear(double unix_time_s) {
  const std::time_t seconds = static_cast<std::time_t>(unix_time_s);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  const int year = utc.tm_year + 1900;
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return year + (utc.tm_yday + (utc.tm_hour + utc.tm_min / 60.0) / 24.0) / (leap ? 366.0 : 365.0);
}

}  // namespace rotors_gazebo_plugins
