// librotors_gazebo_gps_plugin.so (RotorS' rotors_gazebo_plugins/src/gazebo_gps_plugin.cpp): a SensorPlugin in a <sensor
// type="gps">, updated at the sensor's <update_rate>. Publishes <ns>/<gpsTopic> (sensor_msgs/NavSatFix: WGS84 at the
// world's <spherical_coordinates>, fix, GPS service, covariance diag(h^2, h^2, v^2)) and
// <ns>/<groundSpeedTopic> (geometry_msgs/TwistStamped, world-frame velocity), both noisy with the
// plugin's standard deviations and stamped with the sensor's update time. gpsNoiseModel random_walk:
// PX4's Gazebo GPS instead (RandomWalkGpsModel, stepped with the physics; each fix the reading of
// gpsDelay ago), the covariance from horPosStdDev / verPosStdDev as the accuracy the fix reports.
#include <geometry_msgs/TwistStamped.h>
#include <sensor_msgs/NavSatFix.h>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_gazebo_plugins/models/navigation_sensor_models.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/vehicle_bus.h"
#include "rotors_gazebo_plugins/seeded_model.h"
#include "rotors_gazebo_plugins/ros/feed_publisher.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboGpsPlugin : public rotors_sim::SensorPlugin {
 public:
  void Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr /*sdf*/) override {
    if (sensor->Type() != "gps" && sensor->Type() != "navsat")
      throw rotors_sim::SimError("librotors_gazebo_gps_plugin.so belongs in a <sensor type=\"gps\">, not type '" +
                                 sensor->Type() + "'");
    const std::string ns = ReadRobotNamespace(Params());
    std::string gps_topic = "gps", ground_speed_topic = "ground_speed", link_name;
    ReadParam(Params(), "gpsTopic", &gps_topic);
    ReadParam(Params(), "groundSpeedTopic", &ground_speed_topic);
    if (ReadParam(Params(), "linkName", &link_name) && link_name != sensor->ParentName())
      throw rotors_sim::SimError("<linkName> '" + link_name + "' is not the sensor's link '" + sensor->ParentName() +
                                 "'");
    GpsParams p;
    std::string noise_model = "white";
    ReadParam(Params(), "gpsNoiseModel", &noise_model);
    if (noise_model == "random_walk") p.noise_model = GpsNoiseModel::kRandomWalk;
    else if (noise_model != "white")
      throw rotors_sim::SimError("gpsNoiseModel '" + noise_model +
                                 "' is not a GPS noise model: white (RotorS') or random_walk (PX4's Gazebo GPS)");
    ReadParam(Params(), "gpsXYRandomWalk", &p.xy_random_walk);
    ReadParam(Params(), "gpsZRandomWalk", &p.z_random_walk);
    ReadParam(Params(), "gpsXYNoiseDensity", &p.xy_noise_density);
    ReadParam(Params(), "gpsZNoiseDensity", &p.z_noise_density);
    ReadParam(Params(), "gpsVXYNoiseDensity", &p.vxy_noise_density);
    ReadParam(Params(), "gpsVZNoiseDensity", &p.vz_noise_density);
    ReadParam(Params(), "gpsCorrelationTime", &p.correlation_time_steps);
    ReadParam(Params(), "gpsDelay", &p.delay_s);
    ReadParam(Params(), "horPosStdDev", &p.hor_pos_std_dev_m);
    ReadParam(Params(), "verPosStdDev", &p.ver_pos_std_dev_m);
    ReadParam(Params(), "horVelStdDev", &p.hor_vel_std_dev_m_s);
    ReadParam(Params(), "verVelStdDev", &p.ver_vel_std_dev_m_s);
    ThrowIfInvalid(p.Validate());
    sensor_ = sensor;
    rotors_sim::physics::World& world = WorldOf(*sensor);
    const auto& o = world.Origin();
    const GeodeticOrigin origin{o.latitude_deg, o.longitude_deg, o.elevation_m, o.heading_deg};
    if (p.noise_model == GpsNoiseModel::kRandomWalk) random_walk_.Emplace(p, origin, ReadSeed(Params()));
    else model_.Emplace(p, origin, ReadSeed(Params()));
    // the readings go on the vehicle bus, whether or not anyone listens, and from there on ROS
    bus_ = VehicleBus::For(world, ns);
    fix_feed_ = &bus_->sensors.gps.Of(ResolveTopic(ns, gps_topic));
    speed_feed_ = &bus_->sensors.ground_speed.Of(ResolveTopic(ns, ground_speed_topic));
    sensor_msgs::NavSatFix fix;
    fix.header.frame_id = sensor->ParentName();
    fix.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
    fix.status.service = sensor_msgs::NavSatStatus::SERVICE_GPS;
    fix.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
    fix.position_covariance[0] = fix.position_covariance[4] = p.hor_pos_std_dev_m * p.hor_pos_std_dev_m;
    fix.position_covariance[8] = p.ver_pos_std_dev_m * p.ver_pos_std_dev_m;
    fix_publisher_.Start(*fix_feed_, world, ns, gps_topic, fix);
    geometry_msgs::TwistStamped speed;
    speed.header.frame_id = fix.header.frame_id;
    speed_publisher_.Start(*speed_feed_, world, ns, ground_speed_topic, speed);
    accuracy_ = {p.hor_pos_std_dev_m, p.ver_pos_std_dev_m};
    connection_ = sensor->ConnectUpdated([this] { OnUpdate(); });
    if (random_walk_) {
      world_ = &world;
      step_connection_ = rotors_sim::event::Events::ConnectWorldUpdateEnd([this] { OnPhysicsStep(); });
    }
  }

  void Reset() override {
    model_.Reset();
    random_walk_.Reset();
    last_step_s_ = -1.0;
  }

 private:
  Eigen::Vector3d Position() const {
    const auto X_WS = sensor_->WorldPose();
    return {X_WS.Pos().X(), X_WS.Pos().Y(), X_WS.Pos().Z()};
  }
  Eigen::Vector3d Velocity() const {
    const auto v_W = sensor_->ParentLink()->WorldLinearVel();
    return {v_W.X(), v_W.Y(), v_W.Z()};
  }

  /// The random-walk model runs with the physics: every step, as PX4's plugin.
  void OnPhysicsStep() {
    const double t_s = world_->SimTime().Double();
    const double dt_s = last_step_s_ < 0.0 ? world_->Physics().max_step_size_s : t_s - last_step_s_;
    last_step_s_ = t_s;
    if (dt_s > 0.0) random_walk_->Step(t_s, dt_s, Position(), Velocity());
  }

  void OnUpdate() {
    GpsSample m;
    if (random_walk_) {
      if (!random_walk_->Fix(world_->SimTime().Double(), &m)) return;
    } else {
      m = model_->Measure(Position(), Velocity());
    }
    const double t_s = sensor_->LastUpdateTime().Double();
    fix_feed_->Put({m, accuracy_.first, accuracy_.second}, t_s);
    speed_feed_->Put({m.ground_speed_W}, t_s);
  }

  rotors_sim::sensors::SensorPtr sensor_;
  std::shared_ptr<VehicleBus> bus_;
  SensorFeed<GpsReading>* fix_feed_ = nullptr;            ///< on the bus
  SensorFeed<GroundSpeedReading>* speed_feed_ = nullptr;  ///< on the bus
  std::pair<double, double> accuracy_;                    ///< horizontal, vertical 1 sigma [m]
  SeededModel<GpsModel> model_;
  SeededModel<RandomWalkGpsModel> random_walk_;
  rotors_sim::physics::World* world_ = nullptr;
  double last_step_s_ = -1.0;
  rotors_sim::event::ConnectionPtr step_connection_;
  FeedPublisher<GpsReading, sensor_msgs::NavSatFix> fix_publisher_;
  FeedPublisher<GroundSpeedReading, geometry_msgs::TwistStamped> speed_publisher_;
  rotors_sim::event::ConnectionPtr connection_;
};

}  // namespace rotors_gazebo_plugins

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::GazeboGpsPlugin)
