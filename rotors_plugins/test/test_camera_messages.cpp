// The depth plugin's messages from a rendered frame: every point of the cloud lies on a face of the
// box it sees, the disparity is f b / Z, the depth image keeps metres and NaN out of range, and
// camera_info's K and P follow the intrinsics.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>
#include <sensor_msgs/point_cloud2_iterator.h>

#include "rotors_core/error.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/world_loader.h"
#include "rotors_gazebo_plugins/ros/camera_ros.h"

using namespace rotors_sim;
using namespace rotors_gazebo_plugins;

namespace {

// A 1 x 2 x 1.5 m box turned 0.4 rad about z at (4, 0.3, 0.75), seen by a depth camera at
// (0, 0, 1.2) pitched 0.1 rad down; nothing else in the world, so every point is on the box.
const char* kWorld = R"(<?xml version='1.0'?><sdf version='1.6'><world name='w'>
<model name='box'><static>true</static><pose>4 0.3 0.75 0 0 0.4</pose><link name='link'><visual name='v'>
  <geometry><box><size>1 2 1.5</size></box></geometry></visual></link></model>
<model name='rig'><static>true</static><pose>0 0 1.2 0 0.1 0</pose><link name='link'>
  <sensor name='depth' type='depth'><update_rate>30</update_rate><camera name='depth'><horizontal_fov>2</horizontal_fov>
    <image><width>640</width><height>480</height><format>L8</format></image><clip><near>0.01</near><far>10</far></clip>
  </camera></sensor></link></model></world></sdf>)";

/// Distance from p (box frame) to the surface of a box of half sizes h.
double DistanceToSurface(const Eigen::Vector3d& p, const Eigen::Vector3d& h) {
  const Eigen::Vector3d q = p.cwiseAbs() - h;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return std::abs(outside + inside);
}

}  // namespace

TEST(CameraMessages, CloudPointsLieOnTheBoxFacesAndDisparityIsFbOverZ) {
  physics::WorldPtr world = WorldLoader::LoadString(kWorld, "cloud");
  world->Step(1);
  auto sensor = std::dynamic_pointer_cast<sensors::CameraSensor>(world->ModelByName("rig")->Sensors().at(0));
  ASSERT_TRUE(sensor);
  const rendering::RenderedFrame& frame = sensor->Frame(0);
  const rendering::CameraSpec& camera = sensor->Camera(0);

  sensor_msgs::PointCloud2 cloud;
  ToCloudMsg(frame, camera, 0.5, 10.0, &cloud);
  ASSERT_EQ(cloud.width * cloud.height, 640u * 480u);
  // optical frame -> world: X_WO = X_WC X_CO
  const ignition::math::Pose3d X_WO = rendering::OpticalInCamera() + sensor->CameraWorldPose(0);
  const ignition::math::Pose3d X_WB(4, 0.3, 0.75, 0, 0, 0.4);
  const Eigen::Vector3d half(0.5, 1.0, 0.75);
  int on_box = 0;
  double worst = 0;
  for (sensor_msgs::PointCloud2ConstIterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z"); x != x.end();
       ++x, ++y, ++z) {
    if (std::isnan(*x)) continue;
    const ignition::math::Vector3d p_W = X_WO.CoordPositionAdd(ignition::math::Vector3d(*x, *y, *z));
    const ignition::math::Vector3d p_B = X_WB.Rot().RotateVectorReverse(p_W - X_WB.Pos());
    worst = std::max(worst, DistanceToSurface(Eigen::Vector3d(p_B.X(), p_B.Y(), p_B.Z()), half));
    ++on_box;
  }
  std::printf("%d cloud points, farthest from the box surface %.6f m\n", on_box, worst);
  EXPECT_GT(on_box, 5000);
  EXPECT_LT(worst, 0.001);

  // disparity d = f b / Z pixel by pixel; -1 where there is no depth
  stereo_msgs::DisparityImage disparity;
  ToDisparityMsg(frame, camera, 0.11, 0.5, 10.0, &disparity);
  const float* d = reinterpret_cast<const float*>(disparity.image.data.data());
  const double f = camera.intrinsics.FocalLengthPx();
  for (size_t i = 0; i < frame.depth_m.size(); i += 97) {
    const float Z = frame.depth_m[i];
    if (std::isnan(Z)) EXPECT_EQ(d[i], -1.0f);
    else EXPECT_NEAR(d[i], f * 0.11 / Z, 1e-4);
  }
  EXPECT_FLOAT_EQ(disparity.f, static_cast<float>(f));
  EXPECT_FLOAT_EQ(disparity.T, 0.11f);

  // depth image: metres as rendered, NaN outside [min, max]
  sensor_msgs::Image depth;
  ToDepthMsg(frame, 0.5, 4.0, &depth);
  EXPECT_EQ(depth.encoding, "32FC1");
  const float* z = reinterpret_cast<const float*>(depth.data.data());
  for (size_t i = 0; i < frame.depth_m.size(); i += 31) {
    const float Z = frame.depth_m[i];
    if (!std::isnan(Z) && Z >= 0.5f && Z <= 4.0f) EXPECT_EQ(z[i], Z);
    else EXPECT_TRUE(std::isnan(z[i]));
  }

  // camera_info: K from the FOV, P[3] = -f b
  const sensor_msgs::CameraInfo info = CameraInfoMsg(camera, 0.11);
  EXPECT_DOUBLE_EQ(info.K[0], 640 / (2 * std::tan(1.0)));
  EXPECT_DOUBLE_EQ(info.K[2], 319.5);
  EXPECT_DOUBLE_EQ(info.K[5], 239.5);
  EXPECT_DOUBLE_EQ(info.P[3], -info.K[0] * 0.11);
  world->Fini();
}

TEST(CameraMessages, APlainCameraRefusesTheDepthCamerasParameters) {
  // the reader records what a plugin reads; the loader refuses the rest by name: a plain camera
  // does not read <depthImageTopicName> (only the depth plugins do), so it is not silently ignored
  const std::string camera = R"(<?xml version='1.0'?><sdf version='1.6'><world name='w'>
<model name='rig'><static>true</static><link name='link'>
  <sensor name='cam' type='camera'><update_rate>30</update_rate><camera name='cam'><horizontal_fov>1</horizontal_fov>
    <image><width>64</width><height>48</height><format>L8</format></image><clip><near>0.01</near><far>10</far></clip>
  </camera><plugin name='p' filename='libgazebo_ros_camera.so'><cameraName>cam</cameraName><alwaysOn>true</alwaysOn>
  PARAM</plugin></sensor></link></model></world></sdf>)";
  auto with = [&](const std::string& param) {
    std::string w = camera;
    return w.replace(w.find("PARAM"), 5, param);
  };
  WorldLoader::LoadString(with(""), "plain")->Fini();  // <alwaysOn> is Gazebo's, accepted
  std::string error;
  try {
    WorldLoader::LoadString(with("<depthImageTopicName>depth</depthImageTopicName>"), "depth_key")->Fini();
  } catch (const SimError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("unknown parameter <depthImageTopicName>"), std::string::npos) << error;
  EXPECT_NE(error.find("this plugin reads: "), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

TEST(CameraMessages, CameraInfoCarriesTheLensAsPlumbBobAndThePrincipalPointAtItsCentre) {
  rendering::CameraSpec camera;
  camera.intrinsics.width_px = 752;
  camera.intrinsics.height_px = 480;
  camera.intrinsics.horizontal_fov_rad = 1.3962634;
  camera.intrinsics.center_u = 0.52;
  camera.intrinsics.center_v = 0.47;
  camera.distortion.k1 = -0.28;
  camera.distortion.k2 = 0.07;
  camera.distortion.k3 = -0.004;
  camera.distortion.p1 = 0.0012;
  camera.distortion.p2 = -0.0009;
  const sensor_msgs::CameraInfo info = CameraInfoMsg(camera, 0.0);
  EXPECT_EQ(info.distortion_model, "plumb_bob");
  // ROS' plumb_bob order: k1 k2 p1 p2 k3 (OpenCV's distCoeffs)
  EXPECT_EQ(info.D, (std::vector<double>{-0.28, 0.07, 0.0012, -0.0009, -0.004}));
  EXPECT_DOUBLE_EQ(info.K[2], 0.52 * 752 - 0.5);
  EXPECT_DOUBLE_EQ(info.K[5], 0.47 * 480 - 0.5);
  EXPECT_DOUBLE_EQ(info.P[2], info.K[2]);
  EXPECT_DOUBLE_EQ(info.P[6], info.K[5]);
}
