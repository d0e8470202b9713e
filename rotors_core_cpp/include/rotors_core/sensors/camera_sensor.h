// A rendering sensor: SDF <sensor type="camera|multicamera|depth"> with one <camera> (several for
// a multicamera). At each update (its <update_rate> in sim time, right after the physics step,
// so a frame shows the step it is stamped with) it fires Updated; whoever listens asks for the
// images, which are rendered on the first ask of that update and then kept. Nobody asks, nothing
// is rendered.
#pragma once

#include <cstdint>
#include <vector>

#include <sdf/Element.hh>

#include "rotors_core/rendering/camera_model.h"
#include "rotors_core/rendering/renderer.h"
#include "rotors_core/sensors/sensor.h"

namespace rotors_sim {
namespace sensors {

class CameraSensor : public Sensor {
 public:
  /// Reads the <camera> elements of `sensor_sdf`; throws SimError naming the sensor and the problem.
  CameraSensor(std::string name, std::string type, physics::LinkPtr parent, const physics::Pose3d& pose_in_link,
               double update_rate_hz, const sdf::ElementPtr& sensor_sdf);

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

 protected:
  void OnUpdate(const common::Time& sim_time) override;

 private:
  std::vector<rendering::CameraSpec> cameras_;
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
