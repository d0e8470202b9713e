// A rendering sensor: SDF <sensor type="camera|multicamera|depth"> with one <camera> (several for
// a multicamera). At each update (its <update_rate> in sim time, right after the physics step,
// so a frame shows the step it is stamped with) it fires Updated; whoever listens asks for the
// images, which are rendered on the first ask of that update and then kept. Nobody asks, nothing
// is rendered.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <sdf/Element.hh>

#include "rotors_core/rendering/camera_model.h"
#include "rotors_core/rendering/image_sensor_model.h"
#include "rotors_core/rendering/renderer.h"
#include "rotors_core/sensors/sensor.h"

namespace rotors_sim {
namespace sensors {

class CameraSensor : public Sensor {
 public:
  /// Reads the <camera> elements of `sensor_sdf`; throws SimError naming the sensor and the problem.
  CameraSensor(std::string name, std::string type, physics::LinkPtr parent, const physics::Pose3d& pose_in_link,
               double update_rate_hz, const sdf::ElementPtr& sensor_sdf);
  ~CameraSensor() override;

  /// Checks every camera sensor under `element` (a world or model description) and throws SimError
  /// for the first bad one, naming its model, sensor and camera. For descriptions sdformat refuses.
  static void CheckAll(const sdf::ElementPtr& element, const std::string& model = "");

  static bool IsCameraType(const std::string& type) {
    return type == "camera" || type == "multicamera" || type == "depth";
  }
  bool IsDepth() const { return Type() == "depth"; }
  /// A ground-truth depth image beside each camera's image (off by default; a depth sensor always
  /// has one): optical-axis distance per pixel, aligned with the image.
  void SetGroundTruthDepth(bool on);
  bool RendersDepth() const { return IsDepth() || ground_truth_depth_; }

  size_t CameraCount() const { return cameras_.size(); }
  const rendering::CameraSpec& Camera(size_t i) const { return cameras_.at(i); }
  /// Camera frame (x forward, z up) in the world, now.
  physics::Pose3d CameraWorldPose(size_t i) const;
  /// The frame of camera i at the last update (rendered now if not yet); depth when RendersDepth().
  const rendering::RenderedFrame& Frame(size_t i);
  /// Number of the last update (the noise seed of its frames with the sensor's seed).
  uint64_t UpdateCount() const { return update_count_; }
  /// The noise seed of camera i's frame at the last update.
  uint64_t NoiseSeedOf(size_t i) const { return seed_ * 1000003u + update_count_ * 16u + i; }
  void SetNoiseSeed(uint64_t seed) { seed_ = seed; }

  /// The image sensor of every camera of this sensor: exposure and motion blur, rolling shutter,
  /// auto exposure and gain, photon-transfer noise, vignetting, stamp offset and jitter
  /// (docs/sensor_realism.md). Throws SimError naming a bad parameter. Default: none of them.
  void SetImageSensor(const rendering::ImageSensorParams& params);
  const rendering::ImageSensorParams& ImageSensorSettings() const { return image_sensor_params_; }
  /// Camera i's exposure [s] and analog gain of its last frame (0 s: an instant).
  double ExposureS(size_t i) const;
  double AnalogGain(size_t i) const;
  /// Renders of the last frame of camera i (1 without exposure effects).
  int SubframesOf(size_t i) const;
  /// The stamp of camera i's frame at the last update minus that update's time [s] (eq. S6): the
  /// middle of the exposure is the update's time; <timeOffset> and the frame's jitter are added.
  double StampOffsetS(size_t i) const;

 protected:
  void OnUpdate(const common::Time& sim_time) override;
  /// A world reset: the auto exposure back at its power-on values (a reset flight repeats its frames).
  void OnReset() override;

 private:
  /// The cameras through the image sensor model: renders at their exposure plans' instants, drawn
  /// together; each frame exposed and digitised into frames_[i]; each auto exposure stepped.
  void RenderThroughImageSensor(const std::vector<size_t>& cameras);
  void PlanImageSensorRenders(size_t i, std::vector<rendering::FrameRequest>* requests);
  void FinishImageSensorFrame(size_t i);

  std::vector<rendering::CameraSpec> cameras_;
  rendering::ImageSensorParams image_sensor_params_;
  struct ImageSensorState;  // per camera: auto exposure, the sensor model, the last frame's settings
  std::vector<std::unique_ptr<ImageSensorState>> image_sensors_;  ///< empty: RotorS' images
  std::vector<rendering::RenderedFrame> frames_;
  std::vector<uint64_t> rendered_update_;  ///< update count of frames_[i]; 0 = never
  static constexpr uint64_t kNever = UINT64_MAX;
  std::vector<uint64_t> asked_update_;  ///< update count at the last Frame(i) call; kNever: none yet
  uint64_t update_count_ = 0;
  uint64_t seed_ = 0;
  bool ground_truth_depth_ = false;
};
using CameraSensorPtr = std::shared_ptr<CameraSensor>;

}  // namespace sensors
}  // namespace rotors_sim
