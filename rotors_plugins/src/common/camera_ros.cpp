#include "rotors_gazebo_plugins/ros/camera_ros.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <sensor_msgs/image_encodings.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_gazebo_plugins/plugin_params.h"

namespace rotors_gazebo_plugins {

using rotors_sim::SimError;
using rotors_sim::rendering::CameraSpec;
using rotors_sim::rendering::RenderedFrame;

CameraRosParams CameraRosParams::Read(rotors_sim::SdfParams& params, const rotors_sim::sensors::CameraSensor& sensor,
                                      bool depth_plugin) {
  params.Accept("alwaysOn", "gazebo_ros: render when nobody listens; here a camera renders when subscribed");
  CameraRosParams p;
  if (params.Has("robotNamespace")) {
    p.robot_namespace = ReadRobotNamespace(params);
  } else {
    // gazebo_ros gives a plugin without <robotNamespace> the spawn namespace: the model name
    p.robot_namespace = sensor.ParentLink()->GetModel()->GetName();
  }
  ReadParam(params, "cameraName", &p.camera_name);
  ReadParam(params, "imageTopicName", &p.image_topic);
  ReadParam(params, "cameraInfoTopicName", &p.info_topic);
  ReadParam(params, "frameName", &p.frame_name);
  ReadParam(params, "updateRate", &p.update_rate_hz);
  ReadParam(params, "hackBaseline", &p.hack_baseline_m);
  for (const char* zero : {"distortionK1", "distortionK2", "distortionK3", "distortionT1", "distortionT2", "CxPrime",
                           "Cx", "Cy", "focalLength", "borderCrop"}) {
    double value = 0.0;
    ReadParam(params, zero, &value);
    if (value != 0.0)
      throw SimError(std::string("<") + zero + "> " + std::to_string(value) +
                     " is not supported: camera_info is what the image shows, K from horizontal_fov, size and the "
                     "camera's <distortion><center>, D from its <distortion> k1 k2 k3 p1 p2 (put the lens there; "
                     "leave this 0 or remove it)");
  }
  if (!depth_plugin) {
    ReadParam(params, "groundTruthDepth", &p.ground_truth_depth);
    ReadParam(params, "groundTruthDepthTopicName", &p.ground_truth_depth_topic);
  }
  if (depth_plugin) {
    ReadParam(params, "depthImageTopicName", &p.depth_topic);
    ReadParam(params, "depthImageCameraInfoTopicName", &p.depth_info_topic);
    ReadParam(params, "pointCloudTopicName", &p.points_topic);
    ReadParam(params, "disparityTopicName", &p.disparity_topic);
    ReadParam(params, "baseline", &p.baseline_m);
    ReadParam(params, "pointCloudCutoff", &p.cloud_cutoff_min_m);
    ReadParam(params, "pointCloudCutoffMax", &p.cloud_cutoff_max_m);
    if (p.baseline_m < 0 || p.cloud_cutoff_min_m < 0 || p.cloud_cutoff_max_m < 0)
      throw SimError("baseline and pointCloudCutoff(Max) must be >= 0");
  }
  if (p.update_rate_hz < 0) throw SimError("<updateRate> must be >= 0");
  p.image_sensor = ReadImageSensorParams(params);
  return p;
}

rotors_sim::rendering::ImageSensorParams ReadImageSensorParams(rotors_sim::SdfParams& params) {
  using rotors_sim::rendering::ImageSensorParams;
  ImageSensorParams s;
  ReadParam(params, "exposureTime", &s.exposure_s);
  ReadParam(params, "maxSubframes", &s.max_subframes);
  ReadParam(params, "subframesPerPixel", &s.subframes_per_pixel);
  std::string blur = "subframes";
  ReadParam(params, "blurMethod", &blur);
  if (blur == "velocity") {
    s.blur_method = ImageSensorParams::BlurMethod::kVelocityBuffer;
  } else if (blur != "subframes") {
    throw SimError("<blurMethod> '" + blur +
                   "' is not known; use subframes (renders across the exposure) or velocity "
                   "(one render, blurred along each pixel's motion)");
  }
  ReadParam(params, "lineDelay", &s.line_delay_s);
  ReadParam(params, "autoExposure", &s.auto_exposure);
  ReadParam(params, "autoExposureDesiredBin", &s.desired_bin);
  ReadParam(params, "autoExposureLowPass", &s.aec_low_pass);
  ReadParam(params, "autoGainLowPass", &s.agc_low_pass);
  ReadParam(params, "autoExposureUpdateInterval", &s.update_interval_frames);
  ReadParam(params, "rowTime", &s.row_time_s);
  ReadParam(params, "maxShutterWidth", &s.max_shutter_rows);
  ReadParam(params, "maxAnalogGain", &s.max_analog_gain);
  ReadParam(params, "photonNoise", &s.noise);
  ReadParam(params, "fullWellCapacity", &s.full_well_e);
  ReadParam(params, "readNoise", &s.read_noise_e);
  ReadParam(params, "photoResponseNonUniformity", &s.prnu);
  ReadParam(params, "darkSignalNonUniformity", &s.dsnu_e);
  ReadParam(params, "adcBits", &s.adc_bits);
  ReadParam(params, "referenceExposure", &s.reference_exposure_s);
  std::string vignetting = "none";
  ReadParam(params, "vignetting", &vignetting);
  if (vignetting == "cos4") {
    s.vignetting = ImageSensorParams::Vignetting::kCos4;
  } else if (vignetting == "polynomial") {
    s.vignetting = ImageSensorParams::Vignetting::kPolynomial;
  } else if (vignetting != "none") {
    throw SimError("<vignetting> '" + vignetting + "' is not known; use none, cos4 or polynomial");
  }
  ignition::math::Vector3d coefficients;
  if (ReadParam(params, "vignettingCoefficients", &coefficients)) {
    if (s.vignetting != ImageSensorParams::Vignetting::kPolynomial)
      throw SimError("<vignettingCoefficients> belongs to <vignetting>polynomial</vignetting> (this one is '" +
                     vignetting + "')");
    for (int k = 0; k < 3; ++k) s.vignetting_coefficients[k] = coefficients[k];
  }
  ReadParam(params, "timeOffset", &s.time_offset_s);
  ReadParam(params, "stampJitter", &s.stamp_jitter_s);
  const std::string why = s.Validate();
  if (!why.empty()) throw SimError(why);
  return s;
}

sensor_msgs::CameraInfo CameraInfoMsg(const CameraSpec& camera, double baseline_m) {
  const auto& in = camera.intrinsics;
  const Eigen::Matrix3d K = in.K();
  const double f = in.FocalLengthPx();
  sensor_msgs::CameraInfo info;
  info.width = in.width_px;
  info.height = in.height_px;
  info.distortion_model = "plumb_bob";
  info.D = camera.distortion.PlumbBob();  // k1 k2 p1 p2 k3, as the image is distorted
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      info.K[3 * r + c] = K(r, c);
      info.R[3 * r + c] = r == c ? 1.0 : 0.0;
      info.P[4 * r + c] = K(r, c);
    }
  info.P[3] = -f * baseline_m;  // Tx = -f b (stereo: the second camera)
  return info;
}

void ToImageMsg(const RenderedFrame& frame, rotors_sim::rendering::PixelFormat format, sensor_msgs::Image* msg) {
  msg->width = frame.width_px;
  msg->height = frame.height_px;
  msg->encoding = rotors_sim::rendering::RosEncoding(format);
  msg->is_bigendian = 0;
  msg->step = frame.width_px * rotors_sim::rendering::BytesPerPixel(format);
  msg->data = frame.image;
}

namespace {
bool InRange(float z, double min_m, double max_m) {
  return !std::isnan(z) && z >= min_m && (max_m <= 0.0 || z <= max_m);
}
}  // namespace

void ToDepthMsg(const RenderedFrame& frame, double min_m, double max_m, sensor_msgs::Image* msg) {
  msg->width = frame.width_px;
  msg->height = frame.height_px;
  msg->encoding = sensor_msgs::image_encodings::TYPE_32FC1;
  msg->is_bigendian = 0;
  msg->step = frame.width_px * sizeof(float);
  msg->data.resize(frame.depth_m.size() * sizeof(float));
  float* out = reinterpret_cast<float*>(msg->data.data());
  for (size_t i = 0; i < frame.depth_m.size(); ++i)
    out[i] = InRange(frame.depth_m[i], min_m, max_m) ? frame.depth_m[i] : std::numeric_limits<float>::quiet_NaN();
}

void ToCloudMsg(const RenderedFrame& frame, const CameraSpec& camera, double min_m, double max_m,
                sensor_msgs::PointCloud2* msg) {
  const auto& in = camera.intrinsics;
  const double f = in.FocalLengthPx(), cx = in.Cx(), cy = in.Cy();
  sensor_msgs::PointCloud2Modifier modifier(*msg);
  modifier.setPointCloud2FieldsByString(1, "xyz");
  modifier.resize(static_cast<size_t>(frame.width_px) * frame.height_px);
  msg->width = frame.width_px;
  msg->height = frame.height_px;
  msg->row_step = msg->point_step * msg->width;
  msg->is_dense = false;
  sensor_msgs::PointCloud2Iterator<float> x(*msg, "x"), y(*msg, "y"), z(*msg, "z");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < frame.height_px; ++v)
    for (int u = 0; u < frame.width_px; ++u, ++x, ++y, ++z) {
      const float Z = frame.depth_m[static_cast<size_t>(v) * frame.width_px + u];
      if (!InRange(Z, min_m, max_m)) {
        *x = *y = *z = nan;
        continue;
      }
      // back-projection through K: (u, v, 1) Z = K (x, y, Z)
      *x = static_cast<float>((u - cx) * Z / f);
      *y = static_cast<float>((v - cy) * Z / f);
      *z = Z;
    }
}

void ToDisparityMsg(const RenderedFrame& frame, const CameraSpec& camera, double baseline_m, double min_m, double max_m,
                    stereo_msgs::DisparityImage* msg) {
  const double f = camera.intrinsics.FocalLengthPx();
  msg->f = static_cast<float>(f);
  msg->T = static_cast<float>(baseline_m);
  msg->min_disparity = max_m > 0 ? static_cast<float>(f * baseline_m / max_m) : 0.0f;
  msg->max_disparity = min_m > 0 ? static_cast<float>(f * baseline_m / min_m) : std::numeric_limits<float>::infinity();
  msg->delta_d = 0.0f;  // exact, not quantised
  sensor_msgs::Image& d = msg->image;
  d.width = frame.width_px;
  d.height = frame.height_px;
  d.encoding = sensor_msgs::image_encodings::TYPE_32FC1;
  d.step = frame.width_px * sizeof(float);
  d.data.resize(frame.depth_m.size() * sizeof(float));
  float* out = reinterpret_cast<float*>(d.data.data());
  for (size_t i = 0; i < frame.depth_m.size(); ++i) {
    const float Z = frame.depth_m[i];
    out[i] = InRange(Z, min_m, max_m) ? static_cast<float>(f * baseline_m / Z) : -1.0f;  // d = f b / Z
  }
}

std::string JoinTopic(const std::string& prefix, const std::string& topic) {
  if (prefix.empty() || (!topic.empty() && topic.front() == '/')) return topic;
  return prefix + "/" + topic;
}

bool RateLimiter::Due(double t_s) {
  if (rate_hz_ <= 0.0) return true;
  const double period = 1.0 / rate_hz_;
  // time before the last one: the world was reset, and the first update after it is due as after load
  const bool fresh = last_s_ < 0.0 || t_s < last_s_;
  if (!fresh && t_s < next_due_s_ - 1e-9) return false;
  // the next is due one period after this one was due (as the sensors' own rate), so that a sensor
  // at this same rate whose frames come 3, 3, 4, ... steps apart is never thinned, and the mean
  // rate is rate_hz when the period is not a whole number of steps
  next_due_s_ = (!fresh && t_s < next_due_s_ + period) ? next_due_s_ + period : t_s + period;
  last_s_ = t_s;
  return true;
}

bool CameraHasReaders(const std::shared_ptr<ros::NodeHandle>& node, rotors_sim::physics::World& world) {
  return node != nullptr || rotors_sim::MessageTaps::Of(world).Enabled();
}

CameraChannel::CameraChannel(const std::shared_ptr<ros::NodeHandle>& node, rotors_sim::physics::World& world,
                             const CameraRosParams& params, const std::string& prefix, size_t camera_index,
                             const CameraSpec& camera, std::string frame_id, double baseline_m)
    : index_(camera_index), frame_id_(std::move(frame_id)), format_(camera.format) {
  const std::string& ns = params.robot_namespace;
  // the images are tapped only when a reader names them: building one costs a frame's render
  image_pub_ = Advertise<sensor_msgs::Image>(node, ns, JoinTopic(prefix, params.image_topic), world, 2, false, true);
  info_pub_ = Advertise<sensor_msgs::CameraInfo>(node, ns, JoinTopic(prefix, params.info_topic), world, 2, false, true);
  info_ = CameraInfoMsg(camera, baseline_m);
  info_.header.frame_id = frame_id_;
  if (params.ground_truth_depth)
    depth_pub_ = Advertise<sensor_msgs::Image>(node, ns, JoinTopic(prefix, params.ground_truth_depth_topic), world, 2,
                                               false, true);
}

void CameraChannel::Publish(rotors_sim::sensors::CameraSensor& sensor, const ros::Time& stamp) {
  // eq. S6: the middle of the exposure (the update's time) plus the offset and jitter
  const double stamp_s = std::max(0.0, stamp.toSec() + sensor.StampOffsetS(index_));
  info_.header.stamp = sensor.StampOffsetS(index_) == 0.0 ? stamp : ros::Time(stamp_s);
  info_pub_.publish(info_);
  if (image_pub_.getNumSubscribers() > 0) {
    sensor_msgs::ImagePtr image(new sensor_msgs::Image);
    ToImageMsg(sensor.Frame(index_), format_, image.get());
    image->header = info_.header;
    image_pub_.publish(image);
  }
  if (depth_pub_ && depth_pub_.getNumSubscribers() > 0) {
    sensor_msgs::ImagePtr depth(new sensor_msgs::Image);
    ToDepthMsg(sensor.Frame(index_), 0.0, 0.0, depth.get());  // the whole clip range
    depth->header = info_.header;
    depth_pub_.publish(depth);
  }
}

}  // namespace rotors_gazebo_plugins
