#include "msf_updates/ekf/pose_update.h"

#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>

namespace msf_updates {

std::string PoseSensorParams::Validate() const {
  std::ostringstream why;
  if (!p_ic.allFinite()) why << "pose_sensor/init/p_ic is not finite";
  else if (!q_ic.coeffs().allFinite() || std::abs(q_ic.norm() - 1.0) > 1e-3)
    why << "pose_sensor/init/q_ic (w, x, y, z) = (" << q_ic.w() << ", " << q_ic.x() << ", " << q_ic.y() << ", "
        << q_ic.z() << ") must be a unit quaternion";
  else if (!(scale > 0.0) || !std::isfinite(scale))
    why << "pose_sensor/pose_initial_scale = " << scale << " must be > 0";
  else if (!(pose_noise_meas_p > 0.0) || !std::isfinite(pose_noise_meas_p))
    why << "pose_sensor/pose_noise_meas_p = " << pose_noise_meas_p << " must be > 0 m";
  else if (!(pose_noise_meas_q > 0.0) || !std::isfinite(pose_noise_meas_q))
    why << "pose_sensor/pose_noise_meas_q = " << pose_noise_meas_q << " must be > 0 rad";
  else if (!std::isfinite(pose_delay_s) || std::abs(pose_delay_s) > 2.0)
    why << "pose_sensor/pose_delay = " << pose_delay_s << " must be within -2..2 s";
  else if (!(pose_measurement_minimum_dt_s >= 0.0))
    why << "pose_sensor/pose_measurement_minimum_dt = " << pose_measurement_minimum_dt_s << " must be >= 0 s";
  else if (!(mah_threshold > 0.0)) why << "pose_sensor/mah_threshold = " << mah_threshold << " must be > 0";
  return why.str();
}

Matrix6d PoseSensorParams::FixedCovariance() const {
  Matrix6d R = Matrix6d::Zero();
  R.diagonal() << Eigen::Vector3d::Constant(pose_noise_meas_p * pose_noise_meas_p),
      Eigen::Vector3d::Constant(pose_noise_meas_q * pose_noise_meas_q);
  return R;
}

PoseUpdate::PoseUpdate(const PoseSensorParams& params) : params_(params) {
  params_.q_ic.normalize();
  ThrowIfInvalid(params_.Validate());
}

void PoseUpdate::Linearize(const CoreState& x, const PoseMeasurement& z, Vector6d* r,
                           Eigen::Matrix<double, 6, 15>* H) const {
  using namespace idx;
  const Eigen::Matrix3d C_q = x.q_WI.toRotationMatrix();
  const double L = params_.scale;
  // (17): h_p = L (p + C(q) p_ic);  C(q dq(dtheta)) p_ic ~ C(q) p_ic - C(q) [p_ic]x dtheta
  r->head<3>() = z.p_m_W - L * (x.p_W + C_q * params_.p_ic);
  // (18): q_m = q dq(dtheta) q_ic dq_n  ->  Log((q q_ic)^-1 q_m) ~ C(q_ic)^T dtheta + n_q
  r->tail<3>() = QuaternionLog((x.q_WI * params_.q_ic).conjugate() * z.q_m_WC);
  H->setZero();
  H->block<3, 3>(0, kP) = L * Eigen::Matrix3d::Identity();
  H->block<3, 3>(0, kTheta) = -L * C_q * Skew(params_.p_ic);
  H->block<3, 3>(3, kTheta) = params_.q_ic.toRotationMatrix().transpose();
}

UpdateResult PoseUpdate::Apply(CoreState* x, const PoseMeasurement& z, bool gate) const {
  using namespace idx;
  Vector6d r;
  Eigen::Matrix<double, 6, 15> H;
  Linearize(*x, z, &r, &H);
  const Matrix6d S = H * x->P * H.transpose() + z.R;
  const Eigen::LDLT<Matrix6d> S_ldlt(S);
  UpdateResult result;
  result.mahalanobis = std::sqrt(std::max(0.0, r.dot(S_ldlt.solve(r))));
  if (gate && params_.enable_mah_outlier_rejection && result.mahalanobis > params_.mah_threshold) return result;

  // K = P H^T S^-1
  const Eigen::Matrix<double, 15, 6> K = S_ldlt.solve(H * x->P).transpose();
  const Vector15d dx = K * r;
  // Joseph form keeps P symmetric positive definite: P = (I - K H) P (I - K H)^T + K R K^T
  const Matrix15d I_KH = Matrix15d::Identity() - K * H;
  Matrix15d P = I_KH * x->P * I_KH.transpose() + K * z.R * K.transpose();

  x->p_W += dx.segment<3>(kP);
  x->v_W += dx.segment<3>(kV);
  x->q_WI = (x->q_WI * QuaternionExp(dx.segment<3>(kTheta))).normalized();
  x->b_w += dx.segment<3>(kBw);
  x->b_a += dx.segment<3>(kBa);
  // the attitude error is re-expressed about the corrected attitude: G = I - 1/2 [dtheta]x
  Matrix15d G = Matrix15d::Identity();
  G.block<3, 3>(kTheta, kTheta) -= 0.5 * Skew(dx.segment<3>(kTheta));
  P = G * P * G.transpose();
  x->P = 0.5 * (P + P.transpose());
  result.applied = true;
  return result;
}

}  // namespace msf_updates
