// libgazebo_ros_camera.so (gazebo_ros' camera plugin): a <sensor type="camera"> on ROS as
// <ns>/<cameraName>/image_raw and camera_info, frame <frameName> (default
// <ns>/<cameraName>/camera_optical_link), stamped with the sim time of the step the frame shows.
#include "rotors_core/error.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/ros/camera_ros.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboRosCamera : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr /*sdf*/) override {
    sensor_ = std::dynamic_pointer_cast<rotors_sim::sensors::CameraSensor>(sensor);
    if (!sensor_ || sensor_->Type() != "camera")
      throw rotors_sim::SimError("libgazebo_ros_camera.so belongs in a <sensor type=\"camera\">, not type '" +
                                 sensor->Type() + "'");
    const CameraRosParams params = CameraRosParams::Read(Params(), *sensor_, false);
    sensor_->SetGroundTruthDepth(params.ground_truth_depth);
    params.Apply(*sensor_);
    limiter_ = RateLimiter(params.update_rate_hz);
    node_ = MakeNode(params.robot_namespace);
    if (!CameraHasReaders(node_, WorldOf(*sensor_))) return;  // no ROS, no taps: nothing to publish
    const std::string frame =
        !params.frame_name.empty()
            ? params.frame_name
            : JoinTopic(JoinTopic(params.robot_namespace, params.camera_name), "camera_optical_link");
    channel_ = std::make_unique<CameraChannel>(node_, WorldOf(*sensor_), params, params.camera_name, 0,
                                               sensor_->Camera(0), frame, 0.0);
    connection_ = sensor_->ConnectUpdated([this] {
      if (limiter_.Due(sensor_->LastUpdateTime().Double()))
        channel_->Publish(*sensor_, ToRos(sensor_->LastUpdateTime()));
    });
  }

 private:
  rotors_sim::sensors::CameraSensorPtr sensor_;
  std::shared_ptr<ros::NodeHandle> node_;
  std::unique_ptr<CameraChannel> channel_;
  RateLimiter limiter_{0.0};
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboRosCamera)
