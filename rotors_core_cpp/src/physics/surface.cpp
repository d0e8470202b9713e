#include "rotors_core/physics/surface.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rotors_sim {
namespace physics {

std::string SurfaceParams::Validate() const {
  std::ostringstream why;
  if (!(mu >= 0.0) || !(mu2 >= 0.0)) why << "friction mu = " << mu << ", mu2 = " << mu2 << " must be >= 0";
  else if (!(slip1_m_s_N >= 0.0) || !(slip2_m_s_N >= 0.0) || !std::isfinite(slip1_m_s_N) || !std::isfinite(slip2_m_s_N))
    why << "friction slip1 = " << slip1_m_s_N << ", slip2 = " << slip2_m_s_N << " must be >= 0 and finite";
  else if (!(kp_N_m > 0.0) || !std::isfinite(kp_N_m)) why << "contact kp = " << kp_N_m << " N/m must be > 0 and finite";
  else if (!(kd_N_s_m >= 0.0) || !std::isfinite(kd_N_s_m))
    why << "contact kd = " << kd_N_s_m << " N s/m must be >= 0 and finite";
  return why.str();
}

ContactConstraint Combine(const SurfaceParams& a, const SurfaceParams& b, double h_s) {
  ContactConstraint c;
  c.mu = std::min(a.mu, b.mu);
  c.mu2 = std::min(a.mu2, b.mu2);
  // springs in series, dampers in parallel
  const double kp = 1.0 / (1.0 / a.kp_N_m + 1.0 / b.kp_N_m);
  const double kd = a.kd_N_s_m + b.kd_N_s_m;
  // ERP = h kp / (h kp + kd),  CFM = 1 / (h kp + kd)
  c.erp = h_s * kp / (h_s * kp + kd);
  c.cfm = 1.0 / (h_s * kp + kd);
  // friction rows: the same compliance, plus the force-dependent slip
  c.slip1 = c.cfm + std::min(a.slip1_m_s_N, b.slip1_m_s_N);
  c.slip2 = c.cfm + std::min(a.slip2_m_s_N, b.slip2_m_s_N);
  return c;
}

}  // namespace physics
}  // namespace rotors_sim
