// CameraSensor's per-camera image sensor state (camera_image_sensor.cpp); complete wherever a
// CameraSensor is made or destroyed.
#pragma once

#include <cstdint>
#include <vector>

#include "rotors_core/rendering/image_sensor_model.h"
#include "rotors_core/rendering/renderer.h"
#include "rotors_core/sensors/camera_sensor.h"

namespace rotors_sim {
namespace sensors {

struct CameraSensor::ImageSensorState {
  ImageSensorState(const rendering::ImageSensorParams& params, const rendering::CameraSpec& camera, uint64_t seed)
      : auto_exposure(params),
        sensor(params, camera.intrinsics.width_px, camera.intrinsics.height_px, rendering::BytesPerPixel(camera.format),
               camera.intrinsics.FocalLengthPx(), camera.intrinsics.Cx(), camera.intrinsics.Cy(), seed),
        exposure_s(params.exposure_s) {}

  rendering::AutoExposure auto_exposure;
  rendering::ImageSensor sensor;
  double exposure_s, gain = 1.0;                    ///< for the next frame
  double frame_exposure_s = 0.0, frame_gain = 1.0;  ///< of the last frame
  int frame_subframes = 1;
  double near_depth_m = 0.0;  ///< a near depth of the last frame's scene (0: none yet)
  std::vector<rendering::RenderedFrame> renders;
  std::vector<float> light;         ///< the velocity buffer's exposed light
  rendering::CameraSpec noiseless;  ///< the camera without Gazebo's <noise>, as the renders draw it
  rendering::ExposurePlan plan;     ///< this frame's instants
  rendering::CameraTwist twist;     ///< the camera's twist at the update, optical frame
  double image_speed_px_s = 0.0;    ///< the image's fastest point's speed bound at the update
  int frames_since_depth = 0;       ///< frames since the last depth read-back
};

}  // namespace sensors
}  // namespace rotors_sim
