#include "msf_updates/ekf/pose_ekf.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace msf_updates {
namespace {
constexpr double kTimeEpsilon_s = 1e-6;
constexpr std::size_t kMaxPending = 100;
}  // namespace

std::string InitialUncertainty::Validate() const {
  std::ostringstream why;
  if (!(sigma_v_m_s > 0.0)) why << "core/core_init_sigma_v = " << sigma_v_m_s << " must be > 0 m/s";
  else if (!(sigma_b_w_rad_s >= 0.0)) why << "core/core_init_sigma_gyrbias = " << sigma_b_w_rad_s << " must be >= 0";
  else if (!(sigma_b_a_m_s2 >= 0.0)) why << "core/core_init_sigma_accbias = " << sigma_b_a_m_s2 << " must be >= 0";
  return why.str();
}

const char* ToString(PoseStatus status) {
  switch (status) {
    case PoseStatus::kStoredForInit: return "stored for initialisation";
    case PoseStatus::kApplied: return "applied";
    case PoseStatus::kPending: return "pending (newer than the IMU)";
    case PoseStatus::kRejectedOutlier: return "rejected as an outlier";
    case PoseStatus::kTooOld: return "older than the state buffer";
    case PoseStatus::kTooSoon: return "closer than pose_measurement_minimum_dt to the previous one";
  }
  return "?";
}

PoseEkf::PoseEkf(const CoreNoiseParams& core, const PoseSensorParams& pose, const InitialUncertainty& init,
                 double buffer_length_s)
    : propagation_(core), update_(pose), init_(init), buffer_length_s_(buffer_length_s) {
  ThrowIfInvalid(init.Validate());
  if (!(buffer_length_s > 0.0)) throw std::invalid_argument("state buffer length must be > 0 s");
}

std::string PoseEkf::InitializeScale(double scale) {
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    std::ostringstream why;
    why << "scale " << scale << " must be > 0";
    return why.str();
  }
  return Initialize(scale);
}

std::string PoseEkf::InitializeHeight(double height_m) {
  if (!(height_m >= 0.01)) {
    std::ostringstream why;
    why << "height " << height_m << " m is below the minimum of 0.01 m";
    return why.str();
  }
  if (!latest_pose_) return "no pose measurement received yet";
  const double norm = latest_pose_->p_m_W.norm();
  if (norm < 1e-6) return "the latest pose is at the origin: no scale puts it at a height";
  return Initialize(norm / height_m);  // |p_m| = L * height
}

std::string PoseEkf::Initialize(double scale) {
  if (!latest_pose_) return "no pose measurement received yet";
  if (!have_imu_) return "no IMU measurement received yet";
  using namespace idx;
  update_.SetScale(scale);
  const PoseMeasurement& z = *latest_pose_;
  const PoseSensorParams& s = update_.Params();
  CoreState x;
  x.t_s = latest_imu_.t_s;
  // (18) without noise: q = q_m q_ic^-1;  (17): p = p_m / L - C(q) p_ic
  x.q_WI = (z.q_m_WC * s.q_ic.conjugate()).normalized();
  x.p_W = z.p_m_W / scale - x.q_WI.toRotationMatrix() * s.p_ic;
  const Eigen::Matrix3d C_ic = s.q_ic.toRotationMatrix();
  x.P.block<3, 3>(kP, kP) = z.R.topLeftCorner<3, 3>() / (scale * scale);
  x.P.block<3, 3>(kTheta, kTheta) = C_ic * z.R.bottomRightCorner<3, 3>() * C_ic.transpose();
  x.P.block<3, 3>(kV, kV) = Eigen::Matrix3d::Identity() * init_.sigma_v_m_s * init_.sigma_v_m_s;
  if (!propagation_.Params().core_fixed_bias) {
    x.P.block<3, 3>(kBw, kBw) = Eigen::Matrix3d::Identity() * init_.sigma_b_w_rad_s * init_.sigma_b_w_rad_s;
    x.P.block<3, 3>(kBa, kBa) = Eigen::Matrix3d::Identity() * init_.sigma_b_a_m_s2 * init_.sigma_b_a_m_s2;
  }
  buffer_.clear();
  pending_.clear();
  buffer_.push_back({x, latest_imu_, {}});
  last_fused_t_s_ = -1e300;
  return "";
}

bool PoseEkf::AddImu(const ImuReading& u) {
  if (have_imu_ && u.t_s <= latest_imu_.t_s) return false;
  latest_imu_ = u;
  have_imu_ = true;
  if (!Initialized()) return false;
  const Entry& newest = buffer_.back();
  buffer_.push_back({propagation_.Propagate(newest.x, newest.u, u), u, {}});
  while (buffer_.size() > 2 && buffer_.back().x.t_s - buffer_.front().x.t_s > buffer_length_s_) buffer_.pop_front();
  while (!pending_.empty() && pending_.front().t_s <= u.t_s + kTimeEpsilon_s) {
    Fuse(pending_.front());
    pending_.pop_front();
  }
  return true;
}

PoseStatus PoseEkf::AddPose(PoseMeasurement z) {
  z.t_s -= update_.Params().pose_delay_s;
  if (update_.Params().pose_use_fixed_covariance) z.R = update_.Params().FixedCovariance();
  latest_pose_ = z;
  if (!Initialized()) return PoseStatus::kStoredForInit;
  if (z.t_s > buffer_.back().x.t_s + kTimeEpsilon_s) {
    pending_.push_back(z);
    std::sort(pending_.begin(), pending_.end(), [](const auto& a, const auto& b) { return a.t_s < b.t_s; });
    if (pending_.size() > kMaxPending) pending_.pop_front();
    return PoseStatus::kPending;
  }
  return Fuse(z);
}

std::size_t PoseEkf::Nearest(double t_s) const {
  const auto later =
      std::lower_bound(buffer_.begin(), buffer_.end(), t_s, [](const Entry& e, double t) { return e.x.t_s < t; });
  if (later == buffer_.begin()) return 0;
  if (later == buffer_.end()) return buffer_.size() - 1;
  const auto earlier = std::prev(later);
  return static_cast<std::size_t>((t_s - earlier->x.t_s <= later->x.t_s - t_s ? earlier : later) - buffer_.begin());
}

PoseStatus PoseEkf::Fuse(const PoseMeasurement& z) {
  const double half_step = buffer_.size() > 1 ? 0.5 * (buffer_[1].x.t_s - buffer_[0].x.t_s) : kTimeEpsilon_s;
  if (z.t_s < buffer_.front().x.t_s - half_step) return PoseStatus::kTooOld;
  if (z.t_s > last_fused_t_s_ && z.t_s - last_fused_t_s_ < update_.Params().pose_measurement_minimum_dt_s)
    return PoseStatus::kTooSoon;
  const std::size_t k = Nearest(z.t_s);
  const UpdateResult result = update_.Apply(&buffer_[k].x, z, /*gate=*/true);
  last_mahalanobis_ = result.mahalanobis;
  if (!result.applied) return PoseStatus::kRejectedOutlier;
  buffer_[k].updates.push_back(z);
  last_fused_t_s_ = std::max(last_fused_t_s_, z.t_s);
  // re-propagate the states after k from their IMU samples, re-applying their own updates
  for (std::size_t j = k + 1; j < buffer_.size(); ++j) {
    buffer_[j].x = propagation_.Propagate(buffer_[j - 1].x, buffer_[j - 1].u, buffer_[j].u);
    for (const PoseMeasurement& earlier : buffer_[j].updates) update_.Apply(&buffer_[j].x, earlier, /*gate=*/false);
  }
  return PoseStatus::kApplied;
}

}  // namespace msf_updates
