// The mapping, planning and trajectory libraries against known maps: a synthetic box cloud becomes
// exactly the box's leaves; clearance is the distance to a cube; every planned trajectory keeps the
// vehicle's radius from every occupied leaf (checked every centimetre) and keeps its limits.
#include <cmath>
#include <set>
#include <tuple>

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include "rotors_planning/map_builder.h"
#include "rotors_planning/map_metrics.h"
#include "rotors_planning/occupancy_grid.h"
#include "rotors_planning/path_planner.h"
#include "rotors_planning/trajectory.h"
#include "rotors_planning/vehicle_radius.h"

namespace rotors_planning {
namespace {

using Eigen::Vector3d;
using Key = std::tuple<int, int, int>;
constexpr double kRes = 0.125;  // binary-exact, so cell boundaries are exact

/// Cells [i0, i1) x [j0, j1) x [k0, k1) (units of kRes) marked occupied.
octomap::OcTree BoxTree(int i0, int i1, int j0, int j1, int k0, int k1, octomap::OcTree tree = octomap::OcTree(kRes)) {
  for (int i = i0; i < i1; ++i)
    for (int j = j0; j < j1; ++j)
      for (int k = k0; k < k1; ++k) tree.updateNode((i + 0.5) * kRes, (j + 0.5) * kRes, (k + 0.5) * kRes, true);
  return tree;
}

/// The smallest distance from a trajectory sampled every centimetre to any occupied cell.
double SmallestClearance(const OccupancyGrid& grid, const RestToRestTrajectory& trajectory, double search_m) {
  double smallest = search_m;
  for (double t = 0.0;; t += 0.002) {
    const TrajectorySample s = trajectory.Sample(t);
    smallest = std::min(smallest, grid.Clearance_m(s.p_W, search_m));
    if (t >= trajectory.Duration_s()) break;
  }
  return smallest;
}

TEST(MapBuilder, ASyntheticCloudOfABoxBecomesExactlyThatBoxsLeaves) {
  MapBuilderParams params;
  params.resolution_m = kRes;
  MapBuilder builder(params);
  std::vector<Vector3d> cloud;
  std::set<Key> box;
  for (int i = 8; i < 13; ++i)  // x 1.0-1.625, y -0.375-0.375, z 0.25-0.75
    for (int j = -3; j < 3; ++j)
      for (int k = 2; k < 6; ++k) {
        cloud.emplace_back((i + 0.5) * kRes, (j + 0.5) * kRes, (k + 0.5) * kRes);
        box.insert({i, j, k});
      }
  EXPECT_EQ(builder.Insert(cloud, Vector3d(-2.0, 0.1, 0.6)), cloud.size());
  std::set<Key> occupied;
  size_t free_leaves = 0;
  octomap::OcTree tree(builder.Tree());
  tree.expand();  // every leaf at the finest depth (free space may have been pruned)
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) {
      ++free_leaves;
      continue;
    }
    occupied.insert({static_cast<int>(std::floor(it.getX() / kRes)), static_cast<int>(std::floor(it.getY() / kRes)),
                     static_cast<int>(std::floor(it.getZ() / kRes))});
  }
  EXPECT_EQ(occupied, box);
  EXPECT_GT(free_leaves, 20u);  // the rays from the sensor to the box cleared space
}

TEST(MapBuilder, MaxRangeClearsSpaceButMarksNoHitAndBadParametersAreRefused) {
  MapBuilderParams params;
  params.resolution_m = kRes;
  params.max_range_m = 2.0;
  MapBuilder builder(params);
  builder.Insert({Vector3d(5.0, 0.0, 0.0), Vector3d(NAN, 0.0, 0.0)}, Vector3d::Zero());
  const octomap::OcTree& tree = builder.Tree();
  EXPECT_EQ(tree.search(5.0, 0.0, 0.0), nullptr);  // beyond max range: unknown
  ASSERT_NE(tree.search(1.5, 0.0, 0.0), nullptr);  // on the ray, within range: free
  EXPECT_FALSE(tree.isNodeOccupied(tree.search(1.5, 0.0, 0.0)));
  params.prob_hit = 0.4;
  EXPECT_THROW(
      {
        try {
          MapBuilder bad(params);
        } catch (const std::invalid_argument& e) {
          EXPECT_STREQ(e.what(), "sensor_model/hit = 0.4 must be in (0.5, 1]");
          throw;
        }
      },
      std::invalid_argument);
}

TEST(OccupancyGrid, ClearanceIsTheDistanceToTheNearestOccupiedCube) {
  const octomap::OcTree tree = BoxTree(0, 1, 0, 1, 0, 1);  // the cube [0, 0.125]^3
  const OccupancyGrid grid(tree, Vector3d(-2, -2, -2), Vector3d(2, 2, 2));
  EXPECT_EQ(grid.OccupiedCount(), 1u);
  EXPECT_NEAR(grid.Clearance_m({1.125, 0.05, 0.05}, 3.0), 1.0, 1e-12);                           // face
  EXPECT_NEAR(grid.Clearance_m({1.125, 1.125, 0.05}, 3.0), std::sqrt(2.0), 1e-12);               // edge
  EXPECT_NEAR(grid.Clearance_m({-0.3, -0.4, 0.125 + 1.2}, 3.0), std::sqrt(0.25 + 1.44), 1e-12);  // corner
  EXPECT_EQ(grid.Clearance_m({0.06, 0.06, 0.06}, 3.0), 0.0);                                     // inside
  EXPECT_EQ(grid.Clearance_m({1.6, 0.0, 0.0}, 0.5), 0.5);                                        // nothing that close
  EXPECT_TRUE(grid.IsFree({0.7, 0.06, 0.06}, 0.5));
  EXPECT_FALSE(grid.IsFree({0.6, 0.06, 0.06}, 0.5));
}

TEST(PathPlanner, APathThroughAWindowKeepsTheRadiusFromEveryLeafAndTheTrajectoryKeepsItsLimits) {
  // a wall at x 2.0-2.25 spanning y -4..4, z 0..4, with a 1.5 m window at y 1.5..3, z 1.5..3
  octomap::OcTree tree(kRes);
  for (int i = 16; i < 18; ++i)
    for (int j = -32; j < 32; ++j)
      for (int k = 0; k < 32; ++k) {
        const bool window = j >= 12 && j < 24 && k >= 12 && k < 24;
        if (!window) tree.updateNode((i + 0.5) * kRes, (j + 0.5) * kRes, (k + 0.5) * kRes, true);
      }
  const OccupancyGrid grid(tree, Vector3d(-1, -4, 0.5), Vector3d(5, 4, 4));
  PathPlannerParams params;
  params.radius_m = 0.3;
  params.margin_m = 0.1;
  const PathPlanner planner(params);
  const PlannedPath path = planner.Plan(grid, Vector3d(0, 0, 0.1), Vector3d(4, 0, 1));
  ASSERT_TRUE(path.ok) << path.reason;
  EXPECT_GT(path.raw_vertices, 2u);             // the straight line is blocked
  EXPECT_EQ(path.p_W[1], Vector3d(0, 0, 0.5));  // from the ground: climbs into the box first
  TrajectoryLimits limits;
  limits.max_speed_mps = 2.0;
  limits.max_acceleration_mps2 = 1.0;
  const RestToRestTrajectory trajectory(path.p_W, 0.0, M_PI / 2, limits);
  // the climb is below the box (no obstacle there); from the box on, the radius is kept
  const double clearance = SmallestClearance(grid, trajectory, 2.0);
  std::printf("path of %zu vertices (RRT-Connect: %zu), %.2f s, smallest clearance %.3f m (radius %.2f)\n",
              path.p_W.size(), path.raw_vertices, trajectory.Duration_s(), clearance, params.radius_m);
  EXPECT_GE(clearance, params.radius_m);
  double v_max = 0.0, a_max = 0.0, yaw_rate_max = 0.0;
  for (double t = 0.0; t <= trajectory.Duration_s(); t += 0.001) {
    const TrajectorySample s = trajectory.Sample(t);
    v_max = std::max(v_max, s.v_W.norm());
    a_max = std::max(a_max, s.a_W.norm());
    yaw_rate_max = std::max(yaw_rate_max, std::abs(s.yaw_rate_radps));
  }
  EXPECT_LE(v_max, limits.max_speed_mps * (1 + 1e-9));
  EXPECT_LE(a_max, limits.max_acceleration_mps2 * (1 + 1e-9));
  EXPECT_LE(yaw_rate_max, limits.max_yaw_rate_radps * (1 + 1e-9));
  EXPECT_GT(a_max, 0.9 * limits.max_acceleration_mps2);  // as fast as the limits allow
  const TrajectorySample end = trajectory.Sample(trajectory.Duration_s());
  EXPECT_TRUE(end.p_W.isApprox(Vector3d(4, 0, 1)));
  EXPECT_NEAR(end.yaw_rad, M_PI / 2, 1e-12);
  EXPECT_LT(end.v_W.norm() + end.a_W.norm(), 1e-12);
}

TEST(RestToRestTrajectory, VelocityAndAccelerationAreTheDerivativesOfPosition) {
  TrajectoryLimits limits;
  const RestToRestTrajectory trajectory({Vector3d(0, 0, 1), Vector3d(3, 1, 2), Vector3d(3, -2, 2)}, 3.0, -3.0, limits);
  const double h = 1e-5;
  for (double t = 0.05; t < trajectory.Duration_s(); t += 0.37) {
    const TrajectorySample a = trajectory.Sample(t - h), s = trajectory.Sample(t), b = trajectory.Sample(t + h);
    EXPECT_LT((s.v_W - (b.p_W - a.p_W) / (2 * h)).norm(), 1e-6) << t;
    EXPECT_LT((s.a_W - (b.v_W - a.v_W) / (2 * h)).norm(), 1e-5) << t;
  }
  // yaw from 3 rad to -3 rad turns the short way, through pi (0.283 rad)
  EXPECT_NEAR(std::remainder(trajectory.Sample(trajectory.Duration_s()).yaw_rad + 3.0, 2 * M_PI), 0.0, 1e-12);
  EXPECT_GT(trajectory.Sample(1.0).yaw_rate_radps, 0.0);
}

TEST(PathPlanner, BadGoalsAreRefusedWithTheReason) {
  // a closed shell around the cell block x,y,z in [3, 4] m: its inside is free but unreachable
  octomap::OcTree tree(kRes);
  for (int i = 20; i < 36; ++i)
    for (int j = 20; j < 36; ++j)
      for (int k = 20; k < 36; ++k) {
        const bool shell = i == 20 || i == 35 || j == 20 || j == 35 || k == 20 || k == 35;
        if (shell) tree.updateNode((i + 0.5) * kRes, (j + 0.5) * kRes, (k + 0.5) * kRes, true);
      }
  const OccupancyGrid grid(tree, Vector3d(0, 0, 0), Vector3d(6, 6, 6));
  PathPlannerParams params;
  params.radius_m = 0.3;
  params.margin_m = 0.1;
  params.planning_time_s = 0.5;
  const PathPlanner planner(params);
  const Vector3d start(1, 1, 1);
  EXPECT_EQ(planner.Plan(grid, start, Vector3d(7, 1, 1)).reason,
            "goal (7, 1, 1) is outside the map box (0, 0, 0) - (6, 6, 6)");
  EXPECT_EQ(planner.Plan(grid, start, Vector3d(2.4, 3.5, 3.5)).reason,
            "goal (2.4, 3.5, 3.5) is inside or near an obstacle: 0.1 m from an occupied cell, 0.4 m needed (radius 0.3 "
            "+ margin 0.1)");
  const PlannedPath unreachable = planner.Plan(grid, start, Vector3d(3.5, 3.5, 3.5));
  EXPECT_FALSE(unreachable.ok);
  EXPECT_EQ(unreachable.reason.find("no path from (1, 1, 1) to (3.5, 3.5, 3.5) found in 0.5 s"), 0u)
      << unreachable.reason;
  EXPECT_THROW(PathPlanner(PathPlannerParams{-1.0}), std::invalid_argument);
}

TEST(PathPlanner, InThePowerPlantFromTheGroundToTheFirstWaypoint) {
  octomap::OcTree tree(0.25);
  ASSERT_TRUE(tree.readBinary(ROTORS_POWER_PLANT_BT));
  const OccupancyGrid grid(tree, Vector3d(-15, -35, 0.5), Vector3d(35, 15, 30));
  PathPlannerParams params;
  params.radius_m = 0.34;
  const PathPlanner planner(params);
  const PlannedPath path = planner.Plan(grid, Vector3d(0, 0, 0.1), Vector3d(2, -27, 15));
  ASSERT_TRUE(path.ok) << path.reason;
  const RestToRestTrajectory trajectory(path.p_W, 0.0, 0.0, TrajectoryLimits());
  const double clearance = SmallestClearance(grid, trajectory, 3.0);
  std::printf("power plant: %zu vertices (RRT-Connect: %zu) in %.3f s, %.1f s of flight, smallest clearance %.3f m\n",
              path.p_W.size(), path.raw_vertices, path.planning_time_s, trajectory.Duration_s(), clearance);
  EXPECT_GE(clearance, params.radius_m);
}

TEST(MapMetrics, AMapOfTheFaceASensorSawHasFullPrecisionAndRecallOfTheSeenLeaves) {
  // truth: a solid block of 4 x 6 x 4 cells; the sensor at x = -2 sees its front face (x = 1.0)
  const octomap::OcTree truth = BoxTree(8, 12, -3, 3, 2, 6);
  MapBuilderParams params;
  params.resolution_m = kRes;
  MapBuilder builder(params);
  std::vector<Vector3d> face;
  for (int j = -3; j < 3; ++j)
    for (int k = 2; k < 6; ++k) face.emplace_back(8 * kRes + 1e-4, (j + 0.5) * kRes, (k + 0.5) * kRes);
  builder.Insert(face, Vector3d(-2.0, 0.0, 0.5));
  MapMetrics m = CompareMaps(builder.Tree(), truth);
  EXPECT_EQ(m.truth_occupied, 96u);
  EXPECT_EQ(m.built_occupied, 24u);  // the face's cells
  EXPECT_EQ(m.seen_truth, 24u);      // only the face has free space in front of it
  EXPECT_DOUBLE_EQ(m.Precision(), 1.0);
  EXPECT_DOUBLE_EQ(m.Recall(), 1.0);
  // a spurious hit in mid-air: one false positive of 25
  builder.Insert({Vector3d(0.06, 0.06, 0.06)}, Vector3d(-2.0, 0.0, 0.5));
  m = CompareMaps(builder.Tree(), truth);
  EXPECT_DOUBLE_EQ(m.Precision(), 24.0 / 25.0);
  EXPECT_THROW(CompareMaps(octomap::OcTree(0.2), truth), std::invalid_argument);
}

TEST(VehicleRadius, TheFarthestShapeOfCollisionsAndVisualsThroughTheJoints) {
  // a body box and, on a joint 0.2 m out and 0.05 m up, a propeller mesh of unit radius at scale 0.1
  const std::string urdf = R"(<robot name="r">
    <link name="base"><collision><geometry><box size="0.1 0.1 0.16"/></geometry></collision></link>
    <link name="rotor"><visual><geometry><mesh filename="package://p/prop.stl" scale="0.1 0.1 0.1"/></geometry></visual></link>
    <joint name="j" type="continuous"><parent link="base"/><child link="rotor"/><origin xyz="0 0.2 0.05" rpy="0 0 1"/>
      <axis xyz="0 0 1"/></joint></robot>)";
  const double radius = VehicleRadius_m(urdf, [](const std::string& file) {
    EXPECT_EQ(file, "package://p/prop.stl");
    return 1.0;
  });
  EXPECT_NEAR(radius, std::hypot(0.2, 0.05) + 0.1, 1e-12);
  EXPECT_THROW(VehicleRadius_m("<robot name='r'><link name='a'/></robot>", nullptr), std::invalid_argument);
  EXPECT_THROW(VehicleRadius_m("<sdf/>", nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace rotors_planning
