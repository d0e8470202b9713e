// Contact surface of one collision (SDF <surface>) and how two surfaces combine into the
// parameters of a contact constraint. Engine-free: no ODE here.
#pragma once

#include <string>

namespace rotors_sim {
namespace physics {

/// SDF <surface>: <friction><ode><mu>, <mu2>, <slip1>, <slip2> and <contact><ode><kp>, <kd>
/// (SDF 1.6 defaults).
struct SurfaceParams {
  double mu = 1.0;               ///< [-] Coulomb friction coefficient, first friction direction
  double mu2 = 1.0;              ///< [-] second friction direction
  double slip1_m_s_N = 0.0;      ///< [m/(s N)] force-dependent slip, first friction direction
  double slip2_m_s_N = 0.0;      ///< [m/(s N)] second friction direction
  double kp_N_m = 1e12;          ///< [N/m] contact stiffness
  double kd_N_s_m = 1.0;         ///< [N s/m] contact damping
  std::string Validate() const;  ///< empty when valid, else a one-line reason
};

/// The constraint parameters of one contact between two surfaces over a step h.
struct ContactConstraint {
  double mu = 1.0, mu2 = 1.0;
  double erp = 0.2;                 ///< [-] fraction of the penetration corrected per step
  double cfm = 0.0;                 ///< constraint force mixing (compliance) of the normal row
  double slip1 = 0.0, slip2 = 0.0;  ///< compliance of the two friction rows
};

/// Two surfaces in contact, as Gazebo combines them: the smaller friction coefficient; springs in
/// series, dampers in parallel; then the spring-damper as ERP/CFM for an implicit step of h:
///   kp = 1 / (1/kp1 + 1/kp2),   kd = kd1 + kd2
///   ERP = h kp / (h kp + kd),   CFM = 1 / (h kp + kd)
/// The contact is as stiff along the surface as across it: each friction row gets the same CFM,
/// plus the smaller force-dependent slip of the two surfaces. That compliance is what keeps a
/// resting body's redundant friction rows (four corners of a box: 8 rows for 3 tangential DOF)
/// from being singular; without it ODE's direct (Dantzig) LCP solver fails with "LCP internal
/// error, s <= 0" on every step a box rests on the ground.
ContactConstraint Combine(const SurfaceParams& a, const SurfaceParams& b, double h_s);

}  // namespace physics
}  // namespace rotors_sim
