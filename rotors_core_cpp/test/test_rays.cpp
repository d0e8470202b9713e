// Laser sensors against geometry with known answers: ranges to a plane (r = d / (cos v cos h)) and
// to a sphere (the quadratic's root) for every beam, beam angles and ring order, REP 117 limits,
// noise, the rate in sim time, moving models and the sensor's own body, the sweep of a spinning
// lidar on a yawing MAV (de-skewed with ground-truth poses), and one-line errors for bad scans.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include <Eigen/Geometry>

#include "rotors_core/error.h"
#include "rotors_core/geometry/shapes.h"
#include "rotors_core/model_builder.h"
#include "rotors_core/physics/link.h"
#include "rotors_core/physics/model.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/raycast/ray_scene.h"
#include "rotors_core/sensors/ray_sensor.h"
#include "rotors_core/world_loader.h"
#include "test_worlds.h"

using namespace rotors_sim;
using ignition::math::Pose3d;

namespace {

struct Scan {
  int h_samples = 181;
  double h_min = -1.2, h_max = 1.2;
  int v_samples = 1;
  double v_min = 0.0, v_max = 0.0;
  double r_min = 0.1, r_max = 30.0;
  double stddev = 0.0;
  double rate_hz = 10.0;
  std::string Sdf(const std::string& type = "ray") const {
    std::ostringstream s;
    s.precision(17);
    s << "<sensor name='laser' type='" << type << "'><update_rate>" << rate_hz << "</update_rate><ray><scan>"
      << "<horizontal><samples>" << h_samples << "</samples><resolution>1</resolution><min_angle>" << h_min
      << "</min_angle><max_angle>" << h_max << "</max_angle></horizontal>";
    if (v_samples > 0)
      s << "<vertical><samples>" << v_samples << "</samples><min_angle>" << v_min << "</min_angle><max_angle>" << v_max
        << "</max_angle></vertical>";
    s << "</scan><range><min>" << r_min << "</min><max>" << r_max << "</max></range>";
    if (stddev > 0) s << "<noise><type>gaussian</type><mean>0</mean><stddev>" << stddev << "</stddev></noise>";
    s << "</ray></sensor>";
    return s.str();
  }
};

/// A field of view of columns x rows beams within +-half_h_rad and +-half_v_rad.
Scan Field(int columns, double half_h_rad, int rows, double half_v_rad) {
  Scan scan;
  scan.h_samples = columns;
  scan.h_min = -half_h_rad;
  scan.h_max = half_h_rad;
  scan.v_samples = rows;
  scan.v_min = -half_v_rad;
  scan.v_max = half_v_rad;
  return scan;
}

/// A spinning lidar's pattern: `columns` over the full turn (no column twice), `rings` within
/// +-half_fov_rad, 10 Hz.
Scan Spinning(int columns, int rings, double half_fov_rad) {
  Scan scan;
  scan.h_samples = columns;
  scan.h_min = -M_PI;
  scan.h_max = M_PI * (1 - 2.0 / columns);
  scan.v_samples = rings;
  scan.v_min = -half_fov_rad;
  scan.v_max = half_fov_rad;
  scan.rate_hz = 10.0;
  return scan;
}

/// A model "rig" at X_WM (static or a free body) whose link carries `sensor` at X_LS, and a
/// visual box of its own around the sensor (which the sensor must not see).
std::string Rig(const Pose3d& X_WM, const Pose3d& X_LS, const std::string& sensor, bool is_static = true) {
  std::string s = "<model name='rig'><static>" + std::string(is_static ? "true" : "false") + "</static><pose>" +
                  PoseText(X_WM) + "</pose><link name='link'>";
  if (!is_static)
    s += "<inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.02</izz><ixy>0</ixy><ixz>0</ixz>"
         "<iyz>0</iyz></inertia></inertial>";
  s += "<visual name='housing'><geometry><box><size>0.3 0.3 0.3</size></box></geometry></visual>";
  std::string with_pose = sensor;
  with_pose.insert(with_pose.find('>') + 1, "<pose>" + PoseText(X_LS) + "</pose>");
  return s + with_pose + "</link></model>";
}

std::string Box(const std::string& name, const Pose3d& X_WB, const Eigen::Vector3d& size, bool is_static = true) {
  std::ostringstream s;
  s << "<model name='" << name << "'><static>" << (is_static ? "true" : "false") << "</static><pose>" << PoseText(X_WB)
    << "</pose><link name='link'><visual name='v'><geometry><box><size>" << size.transpose()
    << "</size></box></geometry></visual></link></model>";
  return s.str();
}

std::string Sphere(const std::string& name, const Eigen::Vector3d& c, double r) {
  std::ostringstream s;
  s << "<model name='" << name << "'><static>true</static><pose>" << c.transpose()
    << " 0 0 0</pose><link name='link'><visual name='v'><geometry><sphere><radius>" << r
    << "</radius></sphere></geometry></visual></link></model>";
  return s.str();
}

physics::WorldPtr LoadWorld(const std::string& models, double gravity_z = -9.8, double step_s = 0.001) {
  std::string w = WorldSdf(step_s, gravity_z, false, "world");
  return WorldLoader::LoadString(w.substr(0, w.find("</world>")) + models + "</world></sdf>", "rays");
}

sensors::RaySensorPtr TheLaser(const physics::WorldPtr& world) {
  auto sensor = std::dynamic_pointer_cast<sensors::RaySensor>(world->ModelByName("rig")->Sensors().at(0));
  EXPECT_TRUE(sensor);
  return sensor;
}

/// The sensor's frame in the world (rig pose, sensor offset).
Eigen::Isometry3d T_WS(const sensors::RaySensor& laser) { return ToEigen(laser.WorldPose()); }

}  // namespace

TEST(Rays, BeamAnglesRunFromMinToMaxAndRingsFromTheLowest) {
  const Scan scan = Spinning(1800, 16, 0.2617994);
  WorldGuard g{LoadWorld(Rig(Pose3d(), Pose3d(), scan.Sdf()))};
  const sensors::RayScanSpec& spec = TheLaser(g.world)->Spec();
  ASSERT_EQ(spec.horizontal_count, 1800);
  ASSERT_EQ(spec.vertical_count, 16);
  EXPECT_DOUBLE_EQ(spec.HorizontalAngle(0), -M_PI);
  EXPECT_NEAR(spec.HorizontalAngle(1799), scan.h_max, 1e-12);
  EXPECT_NEAR(spec.HorizontalAngle(1) - spec.HorizontalAngle(0), 2 * M_PI / 1800, 1e-12);
  // ring 0 is the lowest beam (velodyne's numbering), 2 degrees apart
  EXPECT_DOUBLE_EQ(spec.VerticalAngle(0), -0.2617994);
  EXPECT_NEAR(spec.VerticalAngle(15), 0.2617994, 1e-12);
  EXPECT_NEAR(spec.VerticalAngle(1) - spec.VerticalAngle(0), 2 * 0.2617994 / 15, 1e-12);
  const Eigen::Vector3d d = spec.Direction_S(450, 0);  // h = -pi/2, v = -15 deg: right and down
  EXPECT_NEAR(d.x(), 0.0, 1e-9);
  EXPECT_NEAR(d.y(), -std::cos(0.2617994), 1e-9);
  EXPECT_NEAR(d.z(), -std::sin(0.2617994), 1e-9);
}

TEST(Rays, RangesToAPlaneAreDistanceOverCosines) {
  // a wall whose face is the plane x = 4 m in front of a rig tilted and turned in the world: in the
  // sensor frame the plane is n . p = d, so the beam along d_S reaches it at r = d / (n . d_S)
  const Pose3d X_WM(0.2, -0.3, 1.5, 0.05, -0.08, 0.3), X_LS(0.04, 0.02, 0.1, 0.0, 0.0, -0.1);
  Scan scan;
  scan.v_samples = 9;
  scan.v_min = -0.3;
  scan.v_max = 0.3;
  WorldGuard g{LoadWorld(Rig(X_WM, X_LS, scan.Sdf()) +
                         Box("wall", Pose3d(4.05, 0, 0, 0, 0, 0), Eigen::Vector3d(0.1, 200, 200)))};
  g.world->Step(1);
  auto laser = TheLaser(g.world);
  ASSERT_EQ(laser->ScanCount(), 1u);
  const Eigen::Isometry3d T = T_WS(*laser);
  const Eigen::Vector3d n_S = T.linear().transpose() * Eigen::Vector3d::UnitX();
  const double d = 4.0 - T.translation().x();
  const sensors::RayScanSpec& spec = laser->Spec();
  double worst = 0.0;
  int beams = 0;
  for (int j = 0; j < spec.vertical_count; ++j)
    for (int i = 0; i < spec.horizontal_count; ++i) {
      const double expected = d / n_S.dot(spec.Direction_S(i, j));
      const float r = laser->LastScan().ranges_m[j * spec.horizontal_count + i];
      if (expected > 0 && expected <= scan.r_max) {
        worst = std::max(worst, std::abs(r - expected));
        ++beams;
      } else {
        EXPECT_EQ(r, INFINITY) << "beam " << i << ", " << j;
      }
    }
  std::printf("[ rays ] plane at %.3f m: %d beams, largest range error %.3g mm\n", d, beams, worst * 1e3);
  EXPECT_GT(beams, 1000);
  EXPECT_LT(worst, 1e-3);
}

TEST(Rays, RangesToASphereAreTheFirstRootOfTheQuadratic) {
  const Eigen::Vector3d c(3.0, 0.4, 1.2);
  const double R = 0.7;
  const Scan scan = Field(121, 0.4, 61, 0.4);
  WorldGuard g{LoadWorld(Rig(Pose3d(0, 0, 1, 0, 0.02, 0.05), Pose3d(), scan.Sdf()) + Sphere("ball", c, R))};
  g.world->Step(1);
  auto laser = TheLaser(g.world);
  const Eigen::Isometry3d T = T_WS(*laser);
  const sensors::RayScanSpec& spec = laser->Spec();
  double worst = 0.0;
  int hits = 0;
  for (int j = 0; j < spec.vertical_count; ++j)
    for (int i = 0; i < spec.horizontal_count; ++i) {
      // |o + r u - c|^2 = R^2: r = -b - sqrt(b^2 - (|o - c|^2 - R^2)), b = u . (o - c)
      const Eigen::Vector3d u = T.linear() * spec.Direction_S(i, j), oc = T.translation() - c;
      const double b = u.dot(oc), disc = b * b - (oc.squaredNorm() - R * R);
      const float r = laser->LastScan().ranges_m[j * spec.horizontal_count + i];
      if (disc < 1e-6) {  // beams that graze the sphere are left out
        if (disc < -1e-3) {
          EXPECT_EQ(r, INFINITY);
        }
        continue;
      }
      worst = std::max(worst, std::abs(r - (-b - std::sqrt(disc))));
      ++hits;
    }
  std::printf("[ rays ] sphere r = %.1f m: %d beams hit, largest range error %.3g mm\n", R, hits, worst * 1e3);
  EXPECT_GT(hits, 1000);
  EXPECT_LT(worst, 1e-3);
}

TEST(Rays, RangesToAMeshFloorAndAHeightmapFollowTheirSurfaces) {
  // two rigs looking down (pitch pi/2: the sensor's x is the world's -z) with 11 x 11 beams: one 3 m
  // over a mesh floor at z = 0.5, one 10 m over a heightmap ramp rising 4 m over 20 m along x
  const std::string ramp =
      "<heightmap><uri>" + RampPgm(33) + "</uri><size>20 20 4</size><pos>1 2 0.5</pos></heightmap>";
  const Scan scan = Field(11, 0.3, 11, 0.3);
  std::string rig2 = Rig(Pose3d(1, 2, 10, 0, M_PI / 2, 0), Pose3d(), scan.Sdf());
  rig2.replace(rig2.find("name='rig'"), 10, "name='rig2'");
  WorldGuard g{
      LoadWorld(Rig(Pose3d(-20, 0, 3, 0, M_PI / 2, 0), Pose3d(), scan.Sdf()) + rig2 +
                "<model name='floor'><static>true</static><pose>-20 0 0 0 0 0</pose><link name='link'><visual name='v'>"
                "<geometry><mesh><uri>" +
                FloorObj(5, 0.5) +
                "</uri></mesh></geometry></visual></link></model>"
                "<model name='terrain'><static>true</static><link name='link'><visual name='v'><geometry>" +
                ramp + "</geometry></visual></link></model>")};
  g.world->Step(1);
  const auto field = geometry::LoadHeightmap(TempDir() / "ramp.pgm", {20, 20, 4}, {1, 2, 0.5});
  double worst_floor = 0.0, worst_terrain = 0.0;
  for (const std::string name : {"rig", "rig2"}) {
    auto laser = std::dynamic_pointer_cast<sensors::RaySensor>(g.world->ModelByName(name)->Sensors().at(0));
    const Eigen::Isometry3d T = T_WS(*laser);
    for (size_t k = 0; k < laser->BeamDirections_S().size(); ++k) {
      const float r = laser->LastScan().ranges_m[k];
      ASSERT_TRUE(std::isfinite(r)) << name << " beam " << k;
      const Eigen::Vector3d p = T * (r * laser->BeamDirections_S()[k]);
      if (name == "rig") worst_floor = std::max(worst_floor, std::abs(p.z() - 0.5));
      else worst_terrain = std::max(worst_terrain, std::abs(p.z() - field->HeightAt(p.x(), p.y())));
    }
  }
  std::printf("[ rays ] 121 beams on a mesh floor: largest height error %.3g mm; on a heightmap: %.3g mm\n",
              worst_floor * 1e3, worst_terrain * 1e3);
  EXPECT_LT(worst_floor, 1e-3);
  EXPECT_LT(worst_terrain, 1e-3);
}

TEST(Rays, OutOfRangeReadingsFollowRep117AndTheHousingIsNotSeen) {
  Scan scan;
  scan.h_samples = 3;
  scan.h_min = -0.1;
  scan.h_max = 0.1;
  scan.r_min = 0.5;
  scan.r_max = 10.0;
  // the rig's own 0.3 m housing encloses the sensor: it is not in view (Gazebo's ray sensor skips
  // its own link); a thin plate 0.3 m ahead is closer than min range, nothing behind within max
  WorldGuard g{LoadWorld(Rig(Pose3d(), Pose3d(), scan.Sdf()) +
                         Box("plate", Pose3d(0.3, 0, 0, 0, 0, 0), Eigen::Vector3d(0.01, 0.02, 0.5)) +
                         Box("far", Pose3d(-20, 0, 0, 0, 0, 0), Eigen::Vector3d(1, 1, 1)))};
  g.world->Step(1);
  const auto& r = TheLaser(g.world)->LastScan().ranges_m;
  EXPECT_EQ(r[1], -INFINITY);  // the plate, closer than min
  EXPECT_EQ(r[0], INFINITY);   // nothing within max
  EXPECT_EQ(r[2], INFINITY);
}

TEST(Rays, MovingModelsAreSeenWhereTheyAreNow) {
  Scan scan;
  scan.h_samples = 1;
  scan.h_min = scan.h_max = 0.0;
  WorldGuard g{LoadWorld(
      Rig(Pose3d(), Pose3d(), scan.Sdf()) + Box("cart", Pose3d(5, 0, 0, 0, 0, 0), Eigen::Vector3d(1, 1, 1), false),
      0.0)};
  g.world->Step(1);
  auto laser = TheLaser(g.world);
  EXPECT_NEAR(laser->LastScan().ranges_m[0], 4.5, 1e-5);
  g.world->ModelByName("cart")->SetWorldPose(Pose3d(2.5, 0, 0, 0, 0, 0));  // moved between two updates
  g.world->Step(1000);                                                     // ten updates at 10 Hz
  EXPECT_EQ(laser->ScanCount(), 11u);
  EXPECT_NEAR(laser->LastScan().ranges_m[0], 2.0, 1e-5);
  // deleted and spawned again (as /gazebo/delete_model and spawn_sdf_model do), now 1 m wide at 7 m
  ASSERT_TRUE(g.world->RemoveModel("cart"));
  g.world->Step(100);
  EXPECT_EQ(laser->LastScan().ranges_m[0], INFINITY);
  const std::string box = Box("cart", Pose3d(), Eigen::Vector3d(2, 1, 1), false);
  ModelBuilder::Spawn(g.world, SpawnRequest{"<sdf version='1.6'>" + box + "</sdf>", "cart", Pose3d(8, 0, 0, 0, 0, 0)});
  g.world->Step(100);
  EXPECT_NEAR(laser->LastScan().ranges_m[0], 7.0, 1e-5);
}

TEST(Rays, TheVehiclesOtherLinksAreSeenButNotTheSensorsOwnLink) {
  // a vehicle of two rigidly joined links: the sensor's (a 0.2 m housing around it) and an arm
  // reaching 0.5 m ahead of it; gpu_ray and lidar sensors are cast like ray sensors
  for (const std::string type : {"gpu_ray", "lidar", "gpu_lidar"}) {
    Scan scan;
    scan.h_samples = 3;
    scan.h_min = -0.5;
    scan.h_max = 0.5;
    scan.r_min = 0.05;
    std::string sensor = scan.Sdf(type);
    if (type == "lidar" || type == "gpu_lidar")  // SDF 1.6+ spells the element <lidar> for these
      for (const std::string tag : {"<ray>", "</ray>"})
        sensor.replace(sensor.find(tag), tag.size(), tag == "<ray>" ? "<lidar>" : "</lidar>");
    const std::string vehicle =
        "<model name='rig'><link name='base'><pose>0.5 0 0 0 0 0</pose><inertial><mass>1</mass></inertial>"
        "<visual name='arm'><geometry><box><size>0.1 0.1 0.1</size></box></geometry></visual></link>"
        "<link name='lidar'><inertial><mass>0.01</mass></inertial><visual name='housing'><geometry><box><size>0.2 0.2 "
        "0.2</size></box></geometry></visual>" +
        sensor + "</link><joint name='mount' type='fixed'><parent>base</parent><child>lidar</child></joint></model>";
    WorldGuard g{LoadWorld(vehicle + Box("wall", Pose3d(6.05, 0, 0, 0, 0, 0), Eigen::Vector3d(0.1, 50, 50)), 0.0)};
    g.world->Step(1);
    auto laser = std::dynamic_pointer_cast<sensors::RaySensor>(g.world->ModelByName("rig")->Sensors().at(0));
    ASSERT_TRUE(laser) << type;
    const auto& r = laser->LastScan().ranges_m;
    EXPECT_NEAR(r[1], 0.45, 1e-5) << type;                 // the arm's near face, not the housing
    EXPECT_NEAR(r[0], 6.0 / std::cos(0.5), 1e-4) << type;  // beside the arm: the wall
  }
}

TEST(Rays, NoiseIsGaussianWithTheDeclaredSigmaAndRepeatsWithTheSeed) {
  Scan scan = Field(2000, 0.05, 5, 0.05);
  scan.stddev = 0.02;
  auto run = [&](std::vector<double>* errors) {
    WorldGuard g{LoadWorld(Rig(Pose3d(), Pose3d(), scan.Sdf()) +
                           Box("wall", Pose3d(6.05, 0, 0, 0, 0, 0), Eigen::Vector3d(0.1, 50, 50)))};
    g.world->Step(1);
    auto laser = TheLaser(g.world);
    const sensors::RayScanSpec& spec = laser->Spec();
    for (int j = 0; j < spec.vertical_count; ++j)
      for (int i = 0; i < spec.horizontal_count; ++i)
        errors->push_back(laser->LastScan().ranges_m[j * spec.horizontal_count + i] - 6.0 / spec.Direction_S(i, j).x());
  };
  std::vector<double> e, again;
  run(&e);
  run(&again);
  double mean = 0, var = 0;
  for (double x : e) mean += x / e.size();
  for (double x : e) var += (x - mean) * (x - mean) / (e.size() - 1);
  std::printf("[ rays ] %zu noisy ranges: mean %.2f mm, sigma %.3f mm (declared 20 mm)\n", e.size(), mean * 1e3,
              std::sqrt(var) * 1e3);
  EXPECT_NEAR(std::sqrt(var), 0.02, 0.05 * 0.02);
  EXPECT_NEAR(mean, 0.0, 4 * 0.02 / std::sqrt(e.size()));
  EXPECT_EQ(e, again);
}

TEST(Rays, UpdatesFollowTheRateInSimTime) {
  Scan scan;
  scan.h_samples = 10;
  scan.rate_hz = 40.0;
  WorldGuard g{LoadWorld(Rig(Pose3d(), Pose3d(), scan.Sdf()), -9.8, 0.001)};
  auto laser = TheLaser(g.world);
  g.world->Step(1000);
  EXPECT_EQ(laser->ScanCount(), 40u);  // 1 s of sim time at 40 Hz
  laser->SetScanOverTime(true);        // a sweep is published when it ends: one fewer in the next second
  g.world->Step(1000);
  EXPECT_EQ(laser->ScanCount(), 79u);
  // updates at 0.001 + k / 40 s: the last sweep went from 1.951 to 1.976 s
  EXPECT_NEAR(laser->LastScan().start.Double(), 1.951, 1e-9);
  EXPECT_NEAR(laser->LastScan().column_time_s[9], 0.025 * 9 / 10, 1e-7);
}

namespace {
/// A spinning 16-beam lidar at 10 Hz on a free body yawing at 1 rad/s, 4 m from a wall (x = 4);
/// every point put in the world with the body's recorded (ground-truth) pose at the point's time,
/// or, ignoring the time, at the scan's start.
struct Deskew {
  double worst_m = 0.0, worst_ignoring_time_m = 0.0;
  int points = 0;
};

Eigen::Isometry3d Between(const std::map<int64_t, Eigen::Isometry3d>& T_at, double t) {
  auto after = T_at.lower_bound(static_cast<int64_t>(std::ceil(t * 1e9 - 1)));
  auto before = after == T_at.begin() ? after : std::prev(after);
  const double t0 = before->first * 1e-9, t1 = after->first * 1e-9;
  const double a = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(before->second.linear())
                   .slerp(a, Eigen::Quaterniond(after->second.linear()))
                   .toRotationMatrix();
  T.translation() = (1 - a) * before->second.translation() + a * after->second.translation();
  return T;
}

Deskew SpinInFrontOfAWall(bool over_time) {
  const Scan scan = Spinning(900, 16, 0.26);
  WorldGuard g{LoadWorld(Rig(Pose3d(0, 0, 2, 0, 0, 0), Pose3d(0.1, 0, 0.05, 0, 0, 0), scan.Sdf(), false) +
                             Box("wall", Pose3d(4.05, 0, 2, 0, 0, 0), Eigen::Vector3d(0.1, 100, 100)),
                         0.0, 0.001)};
  auto laser = TheLaser(g.world);
  laser->SetScanOverTime(over_time);
  physics::LinkPtr body = g.world->ModelByName("rig")->GetLinks().at(0);
  body->SetWorldAngularVel({0, 0, 1.0});         // about a principal axis: it keeps turning at 1 rad/s
  std::map<int64_t, Eigen::Isometry3d> T_WS_at;  // ground truth, by sim time [ns]
  const Eigen::Isometry3d T_LS = ToEigen(laser->Pose());
  T_WS_at[0] = ToEigen(body->WorldPose()) * T_LS;
  while (laser->ScanCount() < 3) {
    g.world->Step(1);
    T_WS_at[g.world->SimTime().Nanoseconds()] = ToEigen(body->WorldPose()) * T_LS;
  }
  const sensors::RayScanSpec& spec = laser->Spec();
  const sensors::RayScan& s = laser->LastScan();
  const Eigen::Isometry3d T_start = Between(T_WS_at, s.start.Double());
  Deskew out;
  for (int i = 0; i < spec.horizontal_count; ++i) {
    const Eigen::Isometry3d T = Between(T_WS_at, s.start.Double() + s.column_time_s[i]);
    for (int j = 0; j < spec.vertical_count; ++j) {
      const float r = s.ranges_m[j * spec.horizontal_count + i];
      if (!std::isfinite(r)) continue;
      const Eigen::Vector3d p_S = r * spec.Direction_S(i, j);
      out.worst_m = std::max(out.worst_m, std::abs((T * p_S).x() - 4.0));
      out.worst_ignoring_time_m = std::max(out.worst_ignoring_time_m, std::abs((T_start * p_S).x() - 4.0));
      ++out.points;
    }
  }
  return out;
}
}  // namespace

TEST(Rays, ASpinningLidarOnAYawingMavDeskewsOntoTheWall) {
  const Deskew swept = SpinInFrontOfAWall(true), instant = SpinInFrontOfAWall(false);
  std::printf(
      "[ rays ] yawing at 1 rad/s, 4 m from a wall, 10 Hz sweep: points de-skewed with their time lie within %.3g mm "
      "of the wall (%d points); the same points at the scan's start pose, time ignored: %.0f mm. Instantaneous "
      "option: %.3g mm at one pose (no skew to remove)\n",
      swept.worst_m * 1e3, swept.points, swept.worst_ignoring_time_m * 1e3, instant.worst_ignoring_time_m * 1e3);
  EXPECT_GT(swept.points, 1000);
  EXPECT_LT(swept.worst_m, 0.01);
  EXPECT_GT(swept.worst_ignoring_time_m, 0.1);  // the skew that the per-point time removes
  EXPECT_LT(instant.worst_ignoring_time_m, 0.001);
}

TEST(Rays, BadScansAreRefusedWithOneLineNamingTheSensor) {
  auto refused = [](const Scan& scan, const std::string& problem) {
    try {
      LoadWorld(Rig(Pose3d(), Pose3d(), scan.Sdf()));
      ADD_FAILURE() << "accepted: " << problem;
    } catch (const SimError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("sensor 'laser'"), std::string::npos) << what;
      EXPECT_NE(what.find(problem), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  Scan zero;
  zero.h_samples = 0;
  refused(zero, "<samples> is 0");
  Scan angles;
  angles.h_min = 1.0;
  angles.h_max = -1.0;
  refused(angles, "<min_angle> 1 is above <max_angle> -1");
  Scan ranges;
  ranges.r_min = 5.0;
  ranges.r_max = 1.0;
  refused(ranges, "<range><min> 5 m is not below <range><max> 1 m");
}
