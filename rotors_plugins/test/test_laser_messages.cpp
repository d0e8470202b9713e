// The laser plugins' messages against the message definitions: velodyne's PointCloud2 layout (read
// back through sensor_msgs' iterators), LaserScan's angles and REP 117 readings, the block laser's
// PointCloud, Range as the nearest return of a cone cast in a world; and one-line refusals of an
// unknown plugin parameter and of a 3D sensor under the 2D laser plugin.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <sensor_msgs/point_cloud2_iterator.h>

#include "rotors_core/error.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/world_loader.h"
#include "rotors_gazebo_plugins/ros/laser_ros.h"

using namespace rotors_sim;
using namespace rotors_gazebo_plugins;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// 2 rings x 4 columns; column 1 of ring 0 has no return, column 2 of ring 1 is too close.
void TwoRingScan(RayScanSpec* spec, RayScan* scan) {
  spec->horizontal_count = 4;
  spec->horizontal_min_rad = -0.3;
  spec->horizontal_max_rad = 0.3;
  spec->vertical_count = 2;
  spec->vertical_min_rad = -0.1;
  spec->vertical_max_rad = 0.1;
  spec->range_min_m = 0.5;
  spec->range_max_m = 50.0;
  scan->ranges_m = {2.0f, kInf, 3.0f, 4.0f, 5.0f, 6.0f, -kInf, 7.5f};
  scan->intensities = {10, 0, 30, 40, 50, 60, 0, 80};
  scan->column_time_s = {0.0f, 0.025f, 0.05f, 0.075f};
}

}  // namespace

TEST(LaserMessages, VelodyneCloudHasPointXYZIRTsLayoutAndOnlyReturns) {
  RayScanSpec spec;
  RayScan scan;
  TwoRingScan(&spec, &scan);
  sensor_msgs::PointCloud2 msg;
  ToVelodyneCloudMsg(scan, spec, spec.Directions_S(), VelodyneCloudOptions(), &msg);
  using sensor_msgs::PointField;
  const std::vector<std::tuple<std::string, uint32_t, uint8_t>> expected = {
      {"x", 0, PointField::FLOAT32},          {"y", 4, PointField::FLOAT32},    {"z", 8, PointField::FLOAT32},
      {"intensity", 16, PointField::FLOAT32}, {"ring", 20, PointField::UINT16}, {"time", 24, PointField::FLOAT32}};
  ASSERT_EQ(msg.fields.size(), expected.size());
  for (size_t f = 0; f < expected.size(); ++f) {
    EXPECT_EQ(msg.fields[f].name, std::get<0>(expected[f]));
    EXPECT_EQ(msg.fields[f].offset, std::get<1>(expected[f]));
    EXPECT_EQ(msg.fields[f].datatype, std::get<2>(expected[f]));
    EXPECT_EQ(msg.fields[f].count, 1u);
  }
  EXPECT_EQ(msg.point_step, 32u);
  EXPECT_EQ(msg.height, 1u);
  EXPECT_EQ(msg.width, 6u);  // the two beams without a measurable return are dropped
  EXPECT_EQ(msg.row_step, 32u * 6);
  EXPECT_EQ(msg.data.size(), msg.row_step);
  sensor_msgs::PointCloud2ConstIterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z"), intensity(msg, "intensity"),
      time(msg, "time");
  sensor_msgs::PointCloud2ConstIterator<uint16_t> ring(msg, "ring");
  int n = 0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      const float r = scan.ranges_m[j * 4 + i];
      if (!std::isfinite(r)) continue;
      const Eigen::Vector3d p = r * spec.Direction_S(i, j);
      EXPECT_NEAR(*x, p.x(), 1e-6);
      EXPECT_NEAR(*y, p.y(), 1e-6);
      EXPECT_NEAR(*z, p.z(), 1e-6);
      EXPECT_EQ(*intensity, scan.intensities[j * 4 + i]);
      EXPECT_EQ(*ring, j);
      EXPECT_EQ(*time, scan.column_time_s[i]);
      ++x, ++y, ++z, ++intensity, ++time, ++ring, ++n;
    }
  EXPECT_EQ(n, 6);

  VelodyneCloudOptions organised;
  organised.organize = true;
  organised.max_range_m = 7.0;  // the plugin's own max drops the 7.5 m return
  ToVelodyneCloudMsg(scan, spec, spec.Directions_S(), organised, &msg);
  EXPECT_EQ(msg.height, 2u);
  EXPECT_EQ(msg.width, 4u);
  EXPECT_FALSE(msg.is_dense);
  sensor_msgs::PointCloud2ConstIterator<float> ox(msg, "x");
  int nan = 0;
  for (int k = 0; k < 8; ++k, ++ox) nan += std::isnan(*ox);
  EXPECT_EQ(nan, 3);
}

TEST(LaserMessages, LaserScanAnglesSpanTheBeamsAndKeepRep117Readings) {
  RayScanSpec spec;
  RayScan scan;
  TwoRingScan(&spec, &scan);
  spec.vertical_count = 1;
  sensor_msgs::LaserScan msg;
  ToLaserScanMsg(scan, spec, 0.1, true, &msg);
  ASSERT_EQ(msg.ranges.size(), 4u);
  EXPECT_FLOAT_EQ(msg.angle_min, -0.3f);
  EXPECT_FLOAT_EQ(msg.angle_min + 3 * msg.angle_increment, msg.angle_max);
  EXPECT_FLOAT_EQ(msg.angle_max, 0.3f);
  EXPECT_FLOAT_EQ(msg.time_increment, 0.025f);  // a sweep: scan_time / beams
  EXPECT_FLOAT_EQ(msg.scan_time, 0.1f);
  EXPECT_FLOAT_EQ(msg.range_min, 0.5f);
  EXPECT_FLOAT_EQ(msg.range_max, 50.0f);
  EXPECT_EQ(msg.ranges[1], kInf);  // REP 117: nothing within range
  EXPECT_EQ(msg.ranges[2], 3.0f);
  EXPECT_EQ(msg.intensities.size(), 4u);
  ToLaserScanMsg(scan, spec, 0.1, false, &msg);
  EXPECT_EQ(msg.time_increment, 0.0f);  // an instantaneous scan
}

TEST(LaserMessages, BlockLaserCloudHoldsEveryReturnWithItsIntensity) {
  RayScanSpec spec;
  RayScan scan;
  TwoRingScan(&spec, &scan);
  sensor_msgs::PointCloud msg;
  ToBlockCloudMsg(scan, spec, spec.Directions_S(), &msg);
  ASSERT_EQ(msg.points.size(), 6u);
  ASSERT_EQ(msg.channels.size(), 1u);
  EXPECT_EQ(msg.channels[0].name, "intensity");
  EXPECT_EQ(msg.channels[0].values.size(), 6u);
  EXPECT_NEAR(msg.points[0].x, 2.0 * spec.Direction_S(0, 0).x(), 1e-6);
}

namespace {
/// A rig with a 9 x 9 beam cone (+-0.1 rad) and two boxes ahead: a large one at 6 m on the axis and
/// a post at 3 m that only the cone's edge beams reach.
const char* kConeWorld = R"(<?xml version='1.0'?><sdf version='1.6'><world name='w'>
<model name='wall'><static>true</static><pose>6.5 0 0 0 0 0</pose><link name='link'><visual name='v'>
  <geometry><box><size>1 20 20</size></box></geometry></visual></link></model>
<model name='post'><static>true</static><pose>3.05 0.3 0 0 0 0</pose><link name='link'><visual name='v'>
  <geometry><box><size>0.1 0.04 0.02</size></box></geometry></visual></link></model>
<model name='rig'><static>true</static><link name='link'>
  <sensor name='sonar' type='ray'><update_rate>10</update_rate><ray><scan>
    <horizontal><samples>9</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></horizontal>
    <vertical><samples>9</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></vertical></scan>
    <range><min>0.02</min><max>10</max></range></ray>PLUGIN</sensor></link></model></world></sdf>)";

std::string ConeWorld(const std::string& plugin) {
  std::string w = kConeWorld;
  return w.replace(w.find("PLUGIN"), 6, plugin);
}
}  // namespace

TEST(LaserMessages, RangeIsTheNearestReturnOfTheWholeCone) {
  physics::WorldPtr world = WorldLoader::LoadString(ConeWorld(""), "cone");
  world->Step(1);
  auto sensor = std::dynamic_pointer_cast<sensors::RaySensor>(world->ModelByName("rig")->Sensors().at(0));
  ASSERT_TRUE(sensor);
  const RayScan& scan = sensor->LastScan();
  // the centre beam sees the wall at 6 m; the post (front face at x = 3) is off the axis
  EXPECT_NEAR(scan.ranges_m[4 * 9 + 4], 6.0, 1e-4);
  const float nearest = NearestReturn(scan);
  int on_post = 0;
  for (float r : scan.ranges_m) on_post += r < 4.0f;
  EXPECT_GT(on_post, 0);
  // the nearest return is the beam that meets the post's front face x = 3 at the smallest angle
  EXPECT_GT(nearest, 3.0f);
  EXPECT_LT(nearest, 3.0f / std::cos(0.1f) / std::cos(0.1f) + 1e-4f);
  RayScan too_close = scan;
  too_close.ranges_m[7] = -kInf;
  EXPECT_EQ(NearestReturn(too_close), -kInf);
  RayScan nothing = scan;
  nothing.ranges_m.assign(nothing.ranges_m.size(), kInf);
  EXPECT_EQ(NearestReturn(nothing), kInf);
  world->Fini();
}

TEST(LaserMessages, BadPluginParametersAreRefusedWithOneLine) {
  auto refused = [](const std::string& plugin, const std::string& problem) {
    try {
      WorldLoader::LoadString(ConeWorld(plugin), "cone")->Fini();
      ADD_FAILURE() << "accepted: " << plugin;
    } catch (const SimError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("sensor 'sonar'"), std::string::npos) << what;
      EXPECT_NE(what.find(problem), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  refused(
      "<plugin name='p' filename='libgazebo_ros_velodyne_laser.so'><topicName>points</topicName>"
      "<organise_cloud>true</organise_cloud></plugin>",
      "unknown parameter <organise_cloud>");
  refused("<plugin name='p' filename='libgazebo_ros_laser.so'/>", "has 9 vertical samples");
  refused("<plugin name='p' filename='libgazebo_ros_range.so'><radiation>sonar</radiation></plugin>",
          "<radiation> 'sonar' must be ultrasound or infrared");
  refused(
      "<plugin name='p' filename='libgazebo_ros_velodyne_laser.so'><min_range>5</min_range>"
      "<max_range>1</max_range></plugin>",
      "<min_range> 5");
}

TEST(LaserMessages, RotorsLidarModelMeasuresTheDistanceBelowIt) {
  // RotorS' lidar model (models/lidar), turned upside down 2 m above a floor: its beam looks down
  setenv("GAZEBO_MODEL_PATH", RESOURCE_DIR "/../models", 1);
  physics::WorldPtr world = WorldLoader::LoadString(
      R"(<?xml version='1.0'?><sdf version='1.6'><world name='w'>
      <model name='floor'><static>true</static><pose>0 0 -0.5 0 0 0</pose><link name='link'><visual name='v'>
        <geometry><box><size>10 10 1</size></box></geometry></visual></link></model>
      <include><uri>model://lidar</uri><name>lidar</name><static>true</static><pose>0 0 2 3.14159265 0 0</pose></include>
      </world></sdf>)",
      "lidar model");
  auto sensor = std::dynamic_pointer_cast<sensors::RaySensor>(world->ModelByName("lidar")->Sensors().at(0));
  ASSERT_TRUE(sensor);
  EXPECT_DOUBLE_EQ(sensor->UpdateRate(), 20.0);
  EXPECT_DOUBLE_EQ(sensor->Spec().range_min_m, 0.06);
  EXPECT_DOUBLE_EQ(sensor->Spec().range_max_m, 25.0);
  double sum = 0.0;
  int n = 0;
  for (int k = 0; k < 100; ++k) {  // 100 readings at 20 Hz
    world->Step(static_cast<unsigned>(std::lround(0.05 / world->Physics().max_step_size_s)));
    sum += sensor->LastScan().ranges_m.at(0);
    ++n;
  }
  EXPECT_NEAR(sum / n, 2.0, 3 * 0.01 / std::sqrt(n) + 0.005);  // sigma 0.01 m, rounded to 0.01 m
  world->Fini();
}
