// CameraSensor's image sensor (docs/sensor_realism.md): which instants of a frame to render, the
// camera's pose at each (the link's twist at the update, held over the frame's window), the frame
// made from the renders by rendering::ImageSensor, and the auto exposure stepped after it.
#include <algorithm>
#include <cmath>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/sensors/camera_sensor.h"
#include "sensors/camera_image_sensor.h"

namespace rotors_sim {
namespace sensors {

void CameraSensor::SetImageSensor(const rendering::ImageSensorParams& params) {
  const std::string label = Type() + " sensor '" + Name() + "'";
  const std::string why = params.Validate();
  if (!why.empty()) throw SimError(label + ": " + why);
  image_sensor_params_ = params;
  image_sensors_.clear();
  rendered_update_.assign(cameras_.size(), 0);  // this update's frames again, through the sensor
  if (!params.AnyEffect()) return;
  for (size_t i = 0; i < cameras_.size(); ++i) {
    auto state = std::make_unique<ImageSensorState>(params, cameras_[i], seed_ * 31u + i);
    if (params.auto_exposure) state->exposure_s = state->auto_exposure.ExposureS();
    image_sensors_.push_back(std::move(state));
  }
}

void CameraSensor::OnReset() {
  for (auto& s : image_sensors_) {
    s->auto_exposure.Reset();
    s->exposure_s = image_sensor_params_.auto_exposure ? s->auto_exposure.ExposureS() : image_sensor_params_.exposure_s;
    s->gain = 1.0;
    s->near_depth_m = 0.0;
  }
}

double CameraSensor::ExposureS(size_t i) const {
  return image_sensors_.empty() ? 0.0 : image_sensors_.at(i)->frame_exposure_s;
}

double CameraSensor::AnalogGain(size_t i) const {
  return image_sensors_.empty() ? 1.0 : image_sensors_.at(i)->frame_gain;
}

int CameraSensor::SubframesOf(size_t i) const {
  return image_sensors_.empty() ? 1 : image_sensors_.at(i)->frame_subframes;
}

double CameraSensor::StampOffsetS(size_t /*i*/) const {
  // one trigger for every camera of the sensor (a stereo pair's frames share their stamp)
  return rendering::StampOffsetS(image_sensor_params_, NoiseSeedOf(0) ^ 0x5eed5eed5eedULL);
}

void CameraSensor::RenderThroughImageSensor(const std::vector<size_t>& cameras) {
  // every camera's renders first, drawn together (the renderer overlaps them), then each frame
  std::vector<rendering::FrameRequest> requests;
  for (size_t i : cameras) PlanImageSensorRenders(i, &requests);
  physics::World& world = *ParentLink()->GetModel()->GetWorldRaw();
  rendering::Renderer& renderer = rendering::Renderer::Of(world);
  constexpr size_t kRendersPerCall = 8;  // the renderer's targets are bounded
  for (size_t k0 = 0; k0 < requests.size(); k0 += kRendersPerCall)
    renderer.RenderAll(world,
                       std::vector<rendering::FrameRequest>(
                           requests.begin() + k0, requests.begin() + std::min(requests.size(), k0 + kRendersPerCall)));
  for (size_t i : cameras) FinishImageSensorFrame(i);
}

void CameraSensor::PlanImageSensorRenders(size_t i, std::vector<rendering::FrameRequest>* requests) {
  ImageSensorState& s = *image_sensors_.at(i);
  const rendering::ImageSensorParams& p = image_sensor_params_;
  const rendering::CameraIntrinsics& in = cameras_[i].intrinsics;
  s.noiseless = cameras_[i];  // Gazebo's <noise> is added to the frame, not to each render
  s.noiseless.noise_mean = s.noiseless.noise_stddev = 0.0;

  // The camera's twist at the update, held over the frame's window (tens of ms at most):
  // p_C(t) = p_C + v_C t,  R_WC(t) = exp([omega]x t) R_WC,  v_C = v_L + omega x (p_C - p_L)
  const physics::LinkPtr link = ParentLink();
  const physics::Pose3d X_WC = CameraWorldPose(i);
  const physics::Vector3d omega_W = link->WorldAngularVel();
  const physics::Vector3d v_C_W = link->WorldLinearVel() + omega_W.Cross(X_WC.Pos() - link->WorldPose().Pos());
  const physics::Quaterniond q_WO = X_WC.Rot() * rendering::OpticalInCamera().Rot();
  const physics::Vector3d v_O = q_WO.RotateVectorReverse(v_C_W), w_O = q_WO.RotateVectorReverse(omega_W);
  for (int k = 0; k < 3; ++k) {
    s.twist.v_O[k] = v_O[k];
    s.twist.omega_O[k] = w_O[k];
  }
  const double near_m = s.near_depth_m > 0.0 ? s.near_depth_m : in.far_m;
  s.image_speed_px_s = in.ImageSpeedBoundPxS(omega_W.Length(), v_C_W.Length(), near_m);
  if (p.blur_method == rendering::ImageSensorParams::BlurMethod::kVelocityBuffer) {
    // one render at the middle of the exposure, with depth: each pixel is averaged along its motion
    s.plan = rendering::ExposurePlan::Make(0.0, 0.0, in.height_px, 0.0, 1.0, 1);
  } else {
    s.plan = rendering::ExposurePlan::Make(s.exposure_s, p.line_delay_s, in.height_px, s.image_speed_px_s,
                                           p.subframes_per_pixel, p.max_subframes);
  }
  const size_t n = s.plan.times_s.size(), middle = n / 2;
  // the middle render's depth is read back (a cost of its own) when the frame needs it: the depth
  // image, the velocity buffer of an image that may move half a pixel, or, once a second of frames,
  // the scene's near depth for the next frames' motion bound
  const double window_s = s.exposure_s + (in.height_px - 1) * p.line_delay_s;
  const bool blurs = p.blur_method == rendering::ImageSensorParams::BlurMethod::kVelocityBuffer &&
                     s.image_speed_px_s * window_s * p.subframes_per_pixel >= 0.5;
  const bool want_depth = RendersDepth() || blurs || s.frames_since_depth >= 30 || s.near_depth_m <= 0.0;
  s.frames_since_depth = want_depth ? 0 : s.frames_since_depth + 1;
  s.renders.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const double t = s.plan.times_s[k];
    const physics::Vector3d turn = omega_W * t;
    const double angle = turn.Length();
    const physics::Quaterniond q_turn =
        angle > 0.0 ? physics::Quaterniond(turn / angle, angle) : physics::Quaterniond::Identity;
    const physics::Pose3d X_WC_t(X_WC.Pos() + v_C_W * t, q_turn * X_WC.Rot());
    // the middle one with depth: the frame's depth image, the velocity buffer, the next near depth
    requests->push_back({X_WC_t, &s.noiseless, 0, true, k == middle && want_depth, &s.renders[k]});
  }
}

void CameraSensor::FinishImageSensorFrame(size_t i) {
  ImageSensorState& s = *image_sensors_.at(i);
  const rendering::ImageSensorParams& p = image_sensor_params_;
  const rendering::CameraSpec& camera = cameras_[i];
  const rendering::CameraIntrinsics& in = camera.intrinsics;
  rendering::RenderedFrame& out = frames_[i];
  out.width_px = in.width_px;
  out.height_px = in.height_px;
  const size_t renders = s.renders.size(), middle = renders / 2;
  if (p.blur_method == rendering::ImageSensorParams::BlurMethod::kVelocityBuffer) {
    // an image that moves less than half a pixel over the frame's window is the render itself
    if (s.renders[0].depth_m.empty()) {
      s.light.assign(s.renders[0].image.begin(), s.renders[0].image.end());
    } else {
      rendering::VelocityBufferExposure(s.renders[0].image, s.renders[0].depth_m, in.width_px, in.height_px,
                                        rendering::BytesPerPixel(camera.format), in.FocalLengthPx(), in.Cx(), in.Cy(),
                                        s.twist, s.exposure_s, p.line_delay_s, p.subframes_per_pixel, p.max_subframes,
                                        &s.light);
    }
    s.sensor.Digitise(s.light, s.exposure_s, s.gain, NoiseSeedOf(i), &out.image);
  } else {
    std::vector<const std::vector<uint8_t>*> images;
    for (const rendering::RenderedFrame& r : s.renders) images.push_back(&r.image);
    s.sensor.Expose(images, s.plan, s.exposure_s, s.gain, NoiseSeedOf(i), &out.image);
  }
  // with photon noise, the photon-transfer model is the sensor's noise
  if (!p.noise) rendering::AddGazeboNoise(camera.noise_mean, camera.noise_stddev, NoiseSeedOf(i), &out.image);
  out.depth_m.clear();
  if (RendersDepth()) out.depth_m = s.renders[middle].depth_m;
  // a near depth of the scene: the 2nd percentile of the middle render's depths
  std::vector<float> depths;
  for (size_t k = 0; k < s.renders[middle].depth_m.size(); k += 37)
    if (std::isfinite(s.renders[middle].depth_m[k])) depths.push_back(s.renders[middle].depth_m[k]);
  if (!depths.empty()) {
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 50, depths.end());
    s.near_depth_m = std::max(static_cast<double>(depths[depths.size() / 50]), in.near_m);
  }

  s.frame_exposure_s = s.exposure_s;
  s.frame_gain = s.gain;
  s.frame_subframes = static_cast<int>(renders);
  if (p.auto_exposure) {
    double sum = 0.0;
    for (uint8_t value : out.image) sum += value;
    s.auto_exposure.Update(out.image.empty() ? 0.0 : sum / (255.0 * out.image.size()));
    s.exposure_s = s.auto_exposure.ExposureS();
    s.gain = s.auto_exposure.Gain();
  }
}

}  // namespace sensors
}  // namespace rotors_sim
