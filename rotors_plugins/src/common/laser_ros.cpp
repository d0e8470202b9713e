#include "rotors_gazebo_plugins/ros/laser_ros.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "rotors_core/error.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

using rotors_sim::SimError;

void ToLaserScanMsg(const RayScan& scan, const RayScanSpec& spec, double scan_time_s, bool over_time,
                    sensor_msgs::LaserScan* msg) {
  const int n = spec.horizontal_count;
  msg->angle_min = static_cast<float>(spec.horizontal_min_rad);
  msg->angle_max = static_cast<float>(spec.HorizontalAngle(n - 1));
  msg->angle_increment = n > 1 ? static_cast<float>(spec.HorizontalAngle(1) - spec.HorizontalAngle(0)) : 0.0f;
  msg->scan_time = static_cast<float>(scan_time_s);
  msg->time_increment = over_time && n > 0 ? static_cast<float>(scan_time_s / n) : 0.0f;
  msg->range_min = static_cast<float>(spec.range_min_m);
  msg->range_max = static_cast<float>(spec.range_max_m);
  msg->ranges.assign(scan.ranges_m.begin(), scan.ranges_m.begin() + n);
  msg->intensities.assign(scan.intensities.begin(), scan.intensities.begin() + n);
}

namespace {
struct VelodynePoint {  // velodyne_pointcloud::PointXYZIRT as it lies in memory
  float x, y, z, pad;
  float intensity;
  uint16_t ring;
  uint16_t pad2;
  float time;
  float pad3;
};
static_assert(sizeof(VelodynePoint) == 32, "velodyne point layout");

sensor_msgs::PointField Field(const std::string& name, uint32_t offset, uint8_t type) {
  sensor_msgs::PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = type;
  f.count = 1;
  return f;
}
}  // namespace

void ToVelodyneCloudMsg(const RayScan& scan, const RayScanSpec& spec, const std::vector<Eigen::Vector3d>& d_S,
                        const VelodyneCloudOptions& options, sensor_msgs::PointCloud2* msg) {
  using sensor_msgs::PointField;
  msg->fields = {Field("x", offsetof(VelodynePoint, x), PointField::FLOAT32),
                 Field("y", offsetof(VelodynePoint, y), PointField::FLOAT32),
                 Field("z", offsetof(VelodynePoint, z), PointField::FLOAT32),
                 Field("intensity", offsetof(VelodynePoint, intensity), PointField::FLOAT32),
                 Field("ring", offsetof(VelodynePoint, ring), PointField::UINT16),
                 Field("time", offsetof(VelodynePoint, time), PointField::FLOAT32)};
  msg->is_bigendian = false;
  msg->point_step = sizeof(VelodynePoint);
  const int columns = spec.horizontal_count, rings = spec.vertical_count;
  std::vector<VelodynePoint> points;
  points.reserve(static_cast<size_t>(columns) * rings);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // ring by ring (velodyne_simulator's order), each ring by column
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < columns; ++i) {
      const size_t k = static_cast<size_t>(j) * columns + i;
      const float r = scan.ranges_m[k], intensity = scan.intensities[k];
      const bool keep = std::isfinite(r) && r >= options.min_range_m && r <= options.max_range_m &&
                        intensity >= options.min_intensity;
      if (!keep && !options.organize) continue;
      VelodynePoint p{};
      const Eigen::Vector3d p_S = keep ? Eigen::Vector3d(r * d_S[k]) : Eigen::Vector3d::Constant(nan);
      p.x = static_cast<float>(p_S.x());
      p.y = static_cast<float>(p_S.y());
      p.z = static_cast<float>(p_S.z());
      p.intensity = keep ? intensity : nan;
      p.ring = static_cast<uint16_t>(j);
      p.time = scan.column_time_s[i];
      points.push_back(p);
    }
  msg->height = options.organize ? rings : 1;
  msg->width = options.organize ? columns : static_cast<uint32_t>(points.size());
  msg->row_step = msg->point_step * msg->width;
  msg->is_dense = !options.organize;
  msg->data.resize(points.size() * sizeof(VelodynePoint));
  if (!points.empty()) std::memcpy(msg->data.data(), points.data(), msg->data.size());
}

void ToBlockCloudMsg(const RayScan& scan, const RayScanSpec& spec, const std::vector<Eigen::Vector3d>& d_S,
                     sensor_msgs::PointCloud* msg) {
  msg->points.clear();
  msg->channels.assign(1, sensor_msgs::ChannelFloat32());
  msg->channels[0].name = "intensity";
  for (int j = 0; j < spec.vertical_count; ++j)
    for (int i = 0; i < spec.horizontal_count; ++i) {
      const size_t k = static_cast<size_t>(j) * spec.horizontal_count + i;
      if (!std::isfinite(scan.ranges_m[k])) continue;
      const Eigen::Vector3d p = scan.ranges_m[k] * d_S[k];
      geometry_msgs::Point32 point;
      point.x = static_cast<float>(p.x());
      point.y = static_cast<float>(p.y());
      point.z = static_cast<float>(p.z());
      msg->points.push_back(point);
      msg->channels[0].values.push_back(scan.intensities[k]);
    }
}

float NearestReturn(const RayScan& scan) {
  float nearest = std::numeric_limits<float>::infinity();
  for (float r : scan.ranges_m) {
    if (r == -std::numeric_limits<float>::infinity()) return r;  // something is too close to measure
    if (r < nearest) nearest = r;
  }
  return nearest;
}

void AddRangeNoise(double sigma_m, std::mt19937_64* rng, RayScan* scan) {
  if (!(sigma_m > 0.0)) return;
  std::normal_distribution<double> noise(0.0, sigma_m);
  for (float& r : scan->ranges_m)
    if (std::isfinite(r)) r = static_cast<float>(r + noise(*rng));
}

void LaserPlugin::Load(rotors_sim::sensors::SensorPtr sensor, sdf::ElementPtr /*sdf*/) {
  sensor_ = std::dynamic_pointer_cast<rotors_sim::sensors::RaySensor>(sensor);
  if (!sensor_)
    throw SimError(GetFilename() + " belongs in a <sensor type=\"ray\"> (or gpu_ray), not type '" + sensor->Type() +
                   "'");
  robot_namespace_ = sensor_->ParentLink()->GetModel()->GetName();  // gazebo_ros: the spawn namespace
  if (Params().Has("robotNamespace")) robot_namespace_ = ReadRobotNamespace(Params());
  topic_ = DefaultTopic();
  ReadParam(Params(), "topicName", &topic_);
  frame_ = sensor_->ParentName();
  ReadParam(Params(), "frameName", &frame_);
  ReadParam(Params(), "updateRate", &update_rate_hz_);
  if (!(update_rate_hz_ >= 0.0)) throw SimError("<updateRate> " + std::to_string(update_rate_hz_) + " must be >= 0");
  seed_ = std::hash<std::string>()(sensor_->ParentLink()->GetModel()->GetName() + "::" + sensor_->Name() +
                                   "::" + GetHandle());
  rng_.seed(seed_);
  Configure(Params());
  node_ = MakeNode(robot_namespace_);
  if (!Advertise()) return;  // no ROS in this process and no in-process reader: nothing to publish
  connection_ = sensor_->ConnectUpdated([this] {
    if (sensor_->ScanCount() == published_scans_) return;  // a sweep still under way
    published_scans_ = sensor_->ScanCount();
    const double t = sensor_->LastUpdateTime().Double();
    if (update_rate_hz_ > 0.0 && last_published_s_ >= 0.0 && t - last_published_s_ < 1.0 / update_rate_hz_ - 1e-6)
      return;
    last_published_s_ = t;
    // a sweep is stamped with its start, as velodyne_pointcloud and LIO methods expect
    Publish(sensor_->LastScan(), ToRos(sensor_->LastScan().start));
  });
}

void LaserPlugin::Reset() {
  rng_.seed(seed_);
  last_published_s_ = -1.0;
  published_scans_ = 0;
}

bool RangePlugin::Advertise() {
  rotors_sim::physics::World& world = WorldOf(*sensor_);
  bus_ = VehicleBus::For(world, robot_namespace_);
  feed_ = &bus_->sensors.range.Of(ResolveTopic(robot_namespace_, topic_));
  prototype_.header.frame_id = frame_;
  prototype_.min_range = static_cast<float>(sensor_->Spec().range_min_m);  // float32, as sensor_msgs/Range
  prototype_.max_range = static_cast<float>(sensor_->Spec().range_max_m);
  publisher_.Start(*feed_, world, robot_namespace_, topic_, prototype_, 4);
  return true;  // the bus takes every range
}

void RangePlugin::PutRange(float range_m, const ros::Time& stamp) {
  feed_->Put({range_m, prototype_.min_range, prototype_.max_range}, stamp.toSec());
}

}  // namespace rotors_gazebo_plugins
