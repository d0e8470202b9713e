// libgazebo_ros_multicamera.so (gazebo_ros' multicamera plugin): each <camera name="c"> of a
// <sensor type="multicamera"> on ROS as <ns>/<cameraName>/c/image_raw and camera_info. All frames
// of one update carry the same stamp. Every camera after the first gets P[3] = -f <hackBaseline>
// (the right camera of a stereo pair). Frame: <frameName> for all cameras as in gazebo_ros when
// given, else <ns>/<cameraName>/camera_c_optical_link (one frame per camera, as TF needs).
#include "rotors_core/error.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/ros/camera_ros.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboRosMultiCamera : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr /*sdf*/) override {
    sensor_ = std::dynamic_pointer_cast<rotors_sim::sensors::CameraSensor>(sensor);
    if (!sensor_ || sensor_->Type() != "multicamera")
      throw rotors_sim::SimError("libgazebo_ros_multicamera.so belongs in a <sensor type=\"multicamera\">, not type '" +
                                 sensor->Type() + "'");
    const CameraRosParams params = CameraRosParams::Read(Params(), *sensor_, false);
    sensor_->SetGroundTruthDepth(params.ground_truth_depth);
    params.Apply(*sensor_);
    for (size_t i = 0; i < sensor_->CameraCount(); ++i)
      if (sensor_->Camera(i).name.empty())
        throw rotors_sim::SimError("camera " + std::to_string(i) + " of multicamera '" + sensor_->Name() +
                                   "' has no name (its topics are <cameraName>/<name>/...)");
    limiter_ = RateLimiter(params.update_rate_hz);
    node_ = MakeNode(params.robot_namespace);
    if (!CameraHasReaders(node_, WorldOf(*sensor_))) return;  // no ROS, no taps: nothing to publish
    const std::string base = JoinTopic(params.robot_namespace, params.camera_name);
    for (size_t i = 0; i < sensor_->CameraCount(); ++i) {
      const std::string& name = sensor_->Camera(i).name;
      const std::string frame =
          !params.frame_name.empty() ? params.frame_name : JoinTopic(base, "camera_" + name + "_optical_link");
      channels_.push_back(std::make_unique<CameraChannel>(node_, WorldOf(*sensor_), params,
                                                          JoinTopic(params.camera_name, name), i, sensor_->Camera(i),
                                                          frame, i == 0 ? 0.0 : params.hack_baseline_m));
    }
    connection_ = sensor_->ConnectUpdated([this] {
      if (!limiter_.Due(sensor_->LastUpdateTime().Double())) return;
      const ros::Time stamp = ToRos(sensor_->LastUpdateTime());
      for (auto& channel : channels_) channel->Publish(*sensor_, stamp);
    });
  }

 private:
  rotors_sim::sensors::CameraSensorPtr sensor_;
  std::shared_ptr<ros::NodeHandle> node_;
  std::vector<std::unique_ptr<CameraChannel>> channels_;
  RateLimiter limiter_{0.0};
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboRosMultiCamera)
