// What the gazebo_ros camera plugins share: their SDF parameters, the camera_info of a pinhole
// camera, and rendered frames as sensor_msgs (image, 32FC1 depth, PointCloud2, disparity).
#pragma once

#include <memory>
#include <string>

#include <ros/ros.h>

#include <sdf/Element.hh>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <stereo_msgs/DisparityImage.h>

#include "rotors_core/sdf_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"
#include "rotors_core/rendering/camera_model.h"
#include "rotors_core/rendering/renderer.h"
#include "rotors_core/sensors/camera_sensor.h"

namespace rotors_gazebo_plugins {

/// gazebo_ros_camera_utils' parameters. The plugin's distortion and principal-point overrides are
/// refused rather than silently ignored: camera_info follows the camera's own <distortion>.
struct CameraRosParams {
  std::string robot_namespace;  ///< <robotNamespace>, else the model's name (the spawn namespace)
  std::string camera_name;      ///< <cameraName>
  std::string image_topic = "image_raw", info_topic = "camera_info";
  std::string frame_name;        ///< <frameName>; empty: the plugin names the optical frame
  double update_rate_hz = 0.0;   ///< <updateRate>; 0: every sensor update
  double hack_baseline_m = 0.0;  ///< <hackBaseline>: P[3] = -f b of the second camera
  /// ours, camera and multicamera: <groundTruthDepth> publishes a 32FC1 depth image aligned with
  /// each camera's image on <prefix>/<groundTruthDepthTopicName> (default "depth")
  bool ground_truth_depth = false;
  std::string ground_truth_depth_topic = "depth";
  // openni_kinect
  std::string depth_topic = "depth/image_raw", depth_info_topic = "depth/camera_info";
  std::string points_topic = "depth/points", disparity_topic;
  double baseline_m = 0.0, cloud_cutoff_min_m = 0.0, cloud_cutoff_max_m = 0.0;
  /// ours: the image sensor (exposure, blur, rolling shutter, auto exposure, noise, vignetting,
  /// stamp offset and jitter; docs/sensor_realism.md), all off unless set
  rotors_sim::rendering::ImageSensorParams image_sensor;

  /// Reads and checks the plugin's <plugin> element; throws SimError naming a bad or unknown one.
  /// The image sensor's parameters are checked here and set on the sensor by Apply.
  /// `extra_known`: further parameters the calling plugin reads itself.
  static CameraRosParams Read(rotors_sim::SdfParams& params, const rotors_sim::sensors::CameraSensor& sensor,
                              bool depth_plugin);
  /// Sets what the plugin's parameters say on the sensor (the image sensor).
  void Apply(rotors_sim::sensors::CameraSensor& sensor) const { sensor.SetImageSensor(image_sensor); }
};

/// The image sensor's <plugin> parameters (docs/sensor_realism.md); SimError for a bad one.
rotors_sim::rendering::ImageSensorParams ReadImageSensorParams(rotors_sim::SdfParams& params);

/// K from the intrinsics (principal point at the <distortion><center>), P = [K | (-f b, 0, 0)], R = I,
/// D = the camera's plumb_bob coefficients (k1 k2 p1 p2 k3; zeros without <distortion>).
sensor_msgs::CameraInfo CameraInfoMsg(const rotors_sim::rendering::CameraSpec& camera, double baseline_m);
void ToImageMsg(const rotors_sim::rendering::RenderedFrame& frame, rotors_sim::rendering::PixelFormat format,
                sensor_msgs::Image* msg);
/// 32FC1 depth in metres; NaN outside [min, max] (max 0: no upper limit).
void ToDepthMsg(const rotors_sim::rendering::RenderedFrame& frame, double min_m, double max_m, sensor_msgs::Image* msg);
/// An organised cloud (width x height) of x y z in the optical frame, x = (u - cx) Z / f,
/// y = (v - cy) Z / f; NaN outside [min, max].
void ToCloudMsg(const rotors_sim::rendering::RenderedFrame& frame, const rotors_sim::rendering::CameraSpec& camera,
                double min_m, double max_m, sensor_msgs::PointCloud2* msg);
/// d = f b / Z (stereo_msgs/DisparityImage), -1 where there is no depth.
void ToDisparityMsg(const rotors_sim::rendering::RenderedFrame& frame, const rotors_sim::rendering::CameraSpec& camera,
                    double baseline_m, double min_m, double max_m, stereo_msgs::DisparityImage* msg);

/// One camera's image_raw + camera_info publishers (a camera plugin has one, a multicamera one
/// per <camera>). Renders only when someone listens to the image.
class CameraChannel {
 public:
  /// topics under <prefix>/: prefix is "<cameraName>" or "<cameraName>/<camera name>", on ROS when
  /// `node` is not null, and into the world's MessageTaps when a reader names them (the Python
  /// module without ROS: World.listen).
  CameraChannel(const std::shared_ptr<ros::NodeHandle>& node, rotors_sim::physics::World& world,
                const CameraRosParams& params, const std::string& prefix, size_t camera_index,
                const rotors_sim::rendering::CameraSpec& camera, std::string frame_id, double baseline_m);
  void Publish(rotors_sim::sensors::CameraSensor& sensor, const ros::Time& stamp);

 private:
  size_t index_;
  std::string frame_id_;
  rotors_sim::ListenedPublisher image_pub_, info_pub_;
  sensor_msgs::CameraInfo info_;
  rotors_sim::rendering::PixelFormat format_;
  rotors_sim::ListenedPublisher depth_pub_;  ///< ground-truth depth, when asked for
};

/// Whether a camera plugin has anywhere to publish: ROS (`node`), or the world's MessageTaps.
bool CameraHasReaders(const std::shared_ptr<ros::NodeHandle>& node, rotors_sim::physics::World& world);

/// <updateRate> of a plugin below its sensor's rate: true when the next message is due (after a
/// reset, when the time is before the last update's, the next update is due).
class RateLimiter {
 public:
  explicit RateLimiter(double rate_hz) : rate_hz_(rate_hz) {}
  bool Due(double t_s);

 private:
  double rate_hz_, last_s_ = -1.0, next_due_s_ = 0.0;
};

/// A topic under a prefix: "image_raw" under "vi_sensor/left" is "vi_sensor/left/image_raw".
std::string JoinTopic(const std::string& prefix, const std::string& topic);

}  // namespace rotors_gazebo_plugins
