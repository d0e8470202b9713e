// The pose-sensor EKF: IMU propagation plus delayed pose updates. Every IMU sample appends a
// propagated state to a time-ordered buffer; a pose measured at t (header stamp - pose_delay) is
// applied to the buffered state nearest t, and the states after it are re-propagated from their
// IMU samples (re-applying the updates they held), so a late measurement corrects the present.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "msf_updates/ekf/imu_propagation.h"
#include "msf_updates/ekf/pose_update.h"

namespace msf_updates {

/// Initial standard deviations of the states the pose does not give (ours; MSF hard-codes them).
/// Position and attitude start with the covariance of the measurement used for initialisation.
struct InitialUncertainty {
  double sigma_v_m_s = 0.1;       ///< core/core_init_sigma_v
  double sigma_b_w_rad_s = 0.01;  ///< core/core_init_sigma_gyrbias (covers the ADIS turn-on bias, 0.0087)
  double sigma_b_a_m_s2 = 0.2;    ///< core/core_init_sigma_accbias (covers the ADIS turn-on bias, 0.196)
  std::string Validate() const;
};

enum class PoseStatus {
  kStoredForInit,    ///< filter not initialised: kept for the init services
  kApplied,          ///< fused (possibly in the past, with re-propagation)
  kPending,          ///< newer than the newest IMU sample: fused once the IMU catches up
  kRejectedOutlier,  ///< Mahalanobis distance above mah_threshold
  kTooOld,           ///< older than the state buffer
  kTooSoon,          ///< within pose_measurement_minimum_dt of the previous one
};
const char* ToString(PoseStatus status);

class PoseEkf {
 public:
  PoseEkf(const CoreNoiseParams& core, const PoseSensorParams& pose, const InitialUncertainty& init,
          double buffer_length_s = 3.0);

  /// Initialises from the latest pose and IMU sample with the given visual scale (InitScale).
  /// Returns an empty string on success, else why not.
  std::string InitializeScale(double scale);
  /// Initialises with the scale that puts the latest pose at `height_m` (InitHeight; >= 0.01 m).
  std::string InitializeHeight(double height_m);
  bool Initialized() const { return !buffer_.empty(); }

  /// Adds an IMU sample; returns true if the state was propagated to it (false before
  /// initialisation, and for samples not newer than the last one).
  bool AddImu(const ImuReading& u);
  /// Adds a pose; z.t_s is the header stamp (pose_delay is subtracted here).
  PoseStatus AddPose(PoseMeasurement z);

  /// Newest state (valid when Initialized()).
  const CoreState& State() const { return buffer_.back().x; }
  const ImuReading& LatestImu() const { return latest_imu_; }
  /// Mahalanobis distance of the last measurement that was tested.
  double LastMahalanobis() const { return last_mahalanobis_; }
  /// The buffered state nearest t_s (e.g. the state an update was applied to).
  const CoreState& StateAt(double t_s) const { return buffer_[Nearest(t_s)].x; }
  const PoseSensorParams& PoseParams() const { return update_.Params(); }

 private:
  struct Entry {
    CoreState x;
    ImuReading u;
    std::vector<PoseMeasurement> updates;  ///< fused at this entry, re-applied on re-propagation
  };
  std::size_t Nearest(double t_s) const;
  PoseStatus Fuse(const PoseMeasurement& z);
  std::string Initialize(double scale);

  ImuPropagation propagation_;
  PoseUpdate update_;
  InitialUncertainty init_;
  double buffer_length_s_;
  std::deque<Entry> buffer_;
  std::deque<PoseMeasurement> pending_;
  std::optional<PoseMeasurement> latest_pose_;
  ImuReading latest_imu_;
  bool have_imu_ = false;
  double last_fused_t_s_ = -1e300;
  double last_mahalanobis_ = 0.0;
};

}  // namespace msf_updates
