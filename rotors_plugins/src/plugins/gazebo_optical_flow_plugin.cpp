// librotors_gazebo_optical_flow_plugin.so: RotorS' optical flow plugin (an external plugin upstream,
// built only with the PX4 OpticalFlow library): a sensor plugin on a downward camera (RotorS'
// flow_cam: 64 x 64, 100 Hz) that computes the flow with OpenCV (OpticalFlowModel, focal length from
// the camera's horizontal_fov) and publishes an integrated sample at <outputRate> (20 Hz, RotorS')
// as mavros_msgs/OpticalFlowRad on <robotNamespace>/<opticalFlowTopic> (default
// px4flow/raw/optical_flow_rad, the topic mavros gives a PX4Flow). RotorS' MAVLink interface adds
// the gyro integrals and the distance: here gyro fields are 0 and distance is -1 (unknown), as
// MAVLink says for a sensor without them; temperature 20 degC (RotorS' value).
#include <vector>

#include <mavros_msgs/OpticalFlowRad.h>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/plugin.h"
#include "rotors_core/ros/listened_publisher.h"
#include "rotors_core/sensors/camera_sensor.h"
#include "rotors_gazebo_plugins/models/optical_flow_model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/camera_ros.h"
#include "rotors_gazebo_plugins/ros/link_sensor_plugin.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboOpticalFlowPlugin : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr /*sdf*/) override {
    sensor_ = std::dynamic_pointer_cast<rotors_sim::sensors::CameraSensor>(sensor);
    if (!sensor_ || sensor_->Type() != "camera")
      throw rotors_sim::SimError(
          "librotors_gazebo_optical_flow_plugin.so belongs in a <sensor type=\"camera\">, not "
          "type '" +
          sensor->Type() + "'");
    topic_.Read(Params(), "opticalFlowTopic", "px4flow/raw/optical_flow_rad");
    const rotors_sim::rendering::CameraSpec& camera = sensor_->Camera(0);
    OpticalFlowParams p;
    p.focal_length_px = camera.intrinsics.FocalLengthPx();
    ReadParam(Params(), "outputRate", &p.output_rate_hz);
    ReadParam(Params(), "maxFeatures", &p.max_features);
    const std::string why = p.Validate();
    if (!why.empty()) throw rotors_sim::SimError("optical flow on sensor '" + sensor_->Name() + "': " + why);
    model_ = std::make_unique<OpticalFlowModel>(p);
    rotors_sim::physics::World& world = WorldOf(*sensor_);
    // the sample goes on the vehicle bus, whether or not anyone listens, and from there on ROS
    bus_ = VehicleBus::For(world, topic_.Namespace());
    feed_ = &bus_->sensors.optical_flow.Of(topic_.Resolved());
    mavros_msgs::OpticalFlowRad prototype;
    prototype.header.frame_id = topic_.Namespace() + "/" + sensor_->Name();
    prototype.temperature = 2000;  // centi-degC
    publisher_.Start(*feed_, world, topic_.Namespace(), topic_.Topic(), prototype);
    connection_ = sensor_->ConnectUpdated([this] { OnFrame(); });
  }

 private:
  void OnFrame() {
    const rotors_sim::rendering::RenderedFrame& frame = sensor_->Frame(0);
    const int W = frame.width_px, H = frame.height_px;
    const size_t channels = frame.image.size() / (static_cast<size_t>(W) * H);
    const uint8_t* grey = frame.image.data();
    if (channels != 1) {  // an RGB/BGR camera: its luma
      grey_.resize(static_cast<size_t>(W) * H);
      for (size_t i = 0; i < grey_.size(); ++i) {
        const uint8_t* px = &frame.image[i * channels];
        grey_[i] = static_cast<uint8_t>((299 * px[0] + 587 * px[1] + 114 * px[2]) / 1000);
      }
      grey = grey_.data();
    }
    const auto sample = model_->AddFrame(grey, W, H, sensor_->LastUpdateTime().Double());
    if (!sample) return;
    OpticalFlowReading reading;  // no gyro integrals (0) and an unknown distance (-1), as its defaults say
    reading.integration_time_us = sample->integration_time_us;
    reading.integrated_xy_rad = {sample->integrated_x, sample->integrated_y};
    reading.quality = sample->quality;
    feed_->Put(reading, sensor_->LastUpdateTime().Double());
  }

  rotors_sim::sensors::CameraSensorPtr sensor_;
  std::unique_ptr<OpticalFlowModel> model_;
  std::vector<uint8_t> grey_;
  SensorTopic topic_;
  FeedPublisher<OpticalFlowReading, mavros_msgs::OpticalFlowRad> publisher_;
  std::shared_ptr<VehicleBus> bus_;
  SensorFeed<OpticalFlowReading>* feed_ = nullptr;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboOpticalFlowPlugin)
