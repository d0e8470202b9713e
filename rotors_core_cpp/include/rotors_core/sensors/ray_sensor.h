// A laser sensor: SDF <sensor type="ray|gpu_ray|lidar|gpu_lidar"> with its <ray> (or <lidar>)
// element, cast on the CPU through the world's RayScene. Both types are cast the same way (no GPU
// here); both see the visuals the cameras see.
//
// Beam (i, j) of the horizontal and vertical samples points along
//   d_S = (cos v_j cos h_i, cos v_j sin h_i, sin v_j)
// in the sensor frame (Gazebo's convention), with h_i = min + i (max - min) / (n - 1) (min when n = 1),
// likewise v_j. Ranges are kept as REP 117 says: +inf where nothing is within max range, -inf
// where the surface is closer than min range.
//
// Two ways to take a scan:
// - instantaneous (default): at each update every beam is cast from the sensor's pose then;
// - over time (spinning lidars, SetScanOverTime(true)): column i of a scan that starts at t0 and
//   lasts T = 1 / update_rate is cast at t0 + i T / n from the sensor's pose at that time (between
//   two steps, interpolated: position linearly, attitude by slerp), so a moving and turning MAV
//   skews the scan as a real spinning lidar does; each column keeps its time offset i T / n.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <sdf/Element.hh>

#include "rotors_core/raycast/ray_scene.h"
#include "rotors_core/sensors/sensor.h"

namespace rotors_sim {
namespace sensors {

/// Gazebo's <ray>/<lidar> element: the beam pattern, the range limits and the range noise.
struct RayScanSpec {
  int horizontal_count = 1;  ///< <horizontal><samples> x <resolution>
  double horizontal_min_rad = 0.0, horizontal_max_rad = 0.0;
  int vertical_count = 1;
  double vertical_min_rad = 0.0, vertical_max_rad = 0.0;
  double range_min_m = 0.0, range_max_m = 0.0;
  double range_resolution_m = 0.0;  ///< readings are rounded to it (0: not rounded)
  double noise_mean_m = 0.0, noise_stddev_m = 0.0;

  /// Reads the <ray> or <lidar> child of a sensor element; throws SimError("<problem>") for a
  /// missing element, zero samples, min angle above max angle, min range above max range, ...
  static RayScanSpec Parse(const sdf::ElementPtr& sensor);
  double HorizontalAngle(int i) const;              ///< [rad] h_i
  double VerticalAngle(int j) const;                ///< [rad] v_j
  Eigen::Vector3d Direction_S(int i, int j) const;  ///< unit beam direction, sensor frame
  /// Every beam's Direction_S, at index j * horizontal_count + i.
  std::vector<Eigen::Vector3d> Directions_S() const;
  size_t BeamCount() const { return static_cast<size_t>(horizontal_count) * vertical_count; }
};

/// One scan: ranges and intensities per beam (vertical row j, horizontal column i at index
/// j * horizontal_count + i) and each column's time since the scan's start.
struct RayScan {
  common::Time start;                ///< sim time of column 0
  std::vector<float> ranges_m;       ///< REP 117: +inf nothing within max, -inf closer than min
  std::vector<float> intensities;    ///< 0-255: 255 |cos| of the angle between beam and surface normal
  std::vector<float> column_time_s;  ///< [s] per column, since `start`
};

class RaySensor : public Sensor {
 public:
  /// Reads the sensor element; throws SimError naming the sensor and the problem.
  RaySensor(std::string name, std::string type, physics::LinkPtr parent, const physics::Pose3d& pose_in_link,
            double update_rate_hz, const sdf::ElementPtr& sensor_sdf);

  static bool IsRayType(const std::string& type) {
    return type == "ray" || type == "gpu_ray" || type == "lidar" || type == "gpu_lidar";
  }
  /// Checks every ray sensor under `element` (a world or model description) and throws SimError
  /// for the first bad one, naming its model and sensor. For descriptions sdformat refuses.
  static void CheckAll(const sdf::ElementPtr& element, const std::string& model = "");

  const RayScanSpec& Spec() const { return spec_; }
  /// Spinning-lidar timing (see above); off: every beam at the update.
  void SetScanOverTime(bool over_time) { over_time_ = over_time; }
  bool ScanOverTime() const { return over_time_; }
  void SetNoiseSeed(uint64_t seed) { seed_ = seed; }

  /// Scans completed so far; the last one is LastScan().
  uint64_t ScanCount() const { return scan_count_; }
  const RayScan& LastScan() const { return last_; }
  /// Spec().Directions_S(), computed once.
  const std::vector<Eigen::Vector3d>& BeamDirections_S() const { return d_S_; }

 protected:
  void OnStep(const common::Time& sim_time) override;
  void OnUpdate(const common::Time& sim_time) override;
  void OnReset() override;

 private:
  bool SweepsOverTime() const;  ///< over time and a rate to time the sweep by
  void SyncScene();             ///< the world's ray scene up to date, the own link's mask reserved
  void StartScan(const common::Time& start);
  /// Casts column i from the sensor pose T_WS, `time_s` after the scan's start.
  void CastColumn(int i, const Eigen::Isometry3d& T_WS, double time_s);
  void FinishScan();
  /// Measured range from a true one: REP 117 limits, noise, resolution.
  float Measure(double true_range_m);

  RayScanSpec spec_;
  std::vector<Eigen::Vector3d> d_S_;         ///< beam directions, sensor frame, at index j * horizontal_count + i
  std::vector<Eigen::Vector3d> column_d_W_;  ///< one column's directions in the world (scratch)
  std::vector<raycast::RayHit> column_hits_;
  bool over_time_ = false;
  uint64_t seed_ = 0;
  uint32_t skip_own_mask_ = 0xFFFFFFFFu;  ///< RayScene::SkipMask of the parent link (all bits: none yet)
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
  RayScan building_, last_;
  uint64_t scan_count_ = 0;
  bool scanning_ = false;
  int next_column_ = 0;
  common::Time previous_step_time_;
  physics::Pose3d previous_X_WS_;
};
using RaySensorPtr = std::shared_ptr<RaySensor>;

}  // namespace sensors
}  // namespace rotors_sim
