// rotors_planning_bench MAP.bt PAIRS SEED [RADIUS]: the planner on a fixed, seeded set of start/goal
// pairs in a map (e.g. the power plant's octree): pairs drawn uniformly among the cell centres that
// keep the clearance and are connected to the open sky over the map (a flood fill: no points
// inside closed buildings, which no planner can reach), 5 m to 40 m apart. Per pair: solved,
// planning time, path length over the straight line, smallest clearance of the trajectory (sampled
// every 10 ms). Prints one JSON line with the per-pair figures and their summary.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <random>
#include <vector>

#include <octomap/OcTree.h>

#include "read_octree.h"
#include "rotors_planning/occupancy_grid.h"
#include "rotors_planning/path_planner.h"
#include "rotors_planning/trajectory.h"

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: rotors_planning_bench MAP.bt PAIRS SEED [RADIUS]\n");
    return 2;
  }
  const auto tree_ptr = rotors_planning::ReadOcTree("rotors_planning_bench", argv[1]);
  if (!tree_ptr) return 2;
  const octomap::OcTree& tree = *tree_ptr;
  const int pairs = std::atoi(argv[2]);
  const unsigned seed = static_cast<unsigned>(std::atoi(argv[3]));
  rotors_planning::PathPlannerParams params;
  params.radius_m = argc == 5 ? std::atof(argv[4]) : 0.319;  // the firefly's, from its URDF
  params.seed = seed;
  const rotors_planning::PathPlanner planner(params);
  double x0, y0, z0, x1, y1, z1;
  tree.getMetricMin(x0, y0, z0);
  tree.getMetricMax(x1, y1, z1);
  // above the ground cells, below the top of the plant
  const Eigen::Vector3d lo(x0, y0, 0.5), hi(x1, y1, std::min(z1, 30.0));
  const rotors_planning::OccupancyGrid grid(tree, lo, hi);
  // free cell centres connected (6-neighbours) to the top layer of the box
  const double res = grid.Resolution_m();
  const Eigen::Vector3i n = ((hi - lo) / res).array().floor().cast<int>();
  auto centre = [&](int i, int j, int k) {
    return Eigen::Vector3d(lo + res * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
  };
  auto index = [&](int i, int j, int k) { return (static_cast<size_t>(i) * n.y() + j) * n.z() + k; };
  std::vector<uint8_t> state(static_cast<size_t>(n.prod()), 0);  // 0 unvisited, 1 reachable, 2 blocked
  std::deque<Eigen::Vector3i> open;
  for (int i = 0; i < n.x(); ++i)
    for (int j = 0; j < n.y(); ++j) open.emplace_back(i, j, n.z() - 1);
  std::vector<Eigen::Vector3d> reachable;
  while (!open.empty()) {
    const Eigen::Vector3i c = open.front();
    open.pop_front();
    if ((c.array() < 0).any() || (c.array() >= n.array()).any()) continue;
    uint8_t& s = state[index(c.x(), c.y(), c.z())];
    if (s) continue;
    const Eigen::Vector3d p = centre(c.x(), c.y(), c.z());
    s = grid.IsFree(p, params.Clearance_m()) ? 1 : 2;
    if (s == 2) continue;
    if (p.z() >= lo.z() + 0.5) reachable.push_back(p);
    for (const Eigen::Vector3i& d : {Eigen::Vector3i(1, 0, 0), Eigen::Vector3i(-1, 0, 0), Eigen::Vector3i(0, 1, 0),
                                     Eigen::Vector3i(0, -1, 0), Eigen::Vector3i(0, 0, 1), Eigen::Vector3i(0, 0, -1)}) {
      open.push_back(c + d);
    }
  }
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, reachable.size() - 1);
  auto draw = [&] { return reachable[pick(rng)]; };
  std::vector<double> times, ratios, clearances, blocked_ratios;
  int solved = 0, blocked = 0;
  std::printf("{\"pairs\": [");
  for (int i = 0; i < pairs; ++i) {
    Eigen::Vector3d start, goal;
    do {
      start = draw();
      goal = draw();
    } while ((goal - start).norm() < 5.0 || (goal - start).norm() > 40.0);
    const rotors_planning::PlannedPath path = planner.Plan(grid, start, goal);
    double ratio = 0.0, clearance = 0.0;
    if (path.ok) {
      ++solved;
      double length = 0.0;
      for (size_t k = 1; k < path.p_W.size(); ++k) length += (path.p_W[k] - path.p_W[k - 1]).norm();
      ratio = length / (goal - start).norm();
      const rotors_planning::RestToRestTrajectory trajectory(path.p_W, 0.0, 0.0, rotors_planning::TrajectoryLimits());
      clearance = 5.0;
      for (double t = 0.0; t <= trajectory.Duration_s(); t += 0.01) {
        clearance = std::min(clearance, grid.Clearance_m(trajectory.Sample(t).p_W, 5.0));
      }
      times.push_back(path.planning_time_s);
      ratios.push_back(ratio);
      if (path.raw_vertices > 2) blocked_ratios.push_back(ratio);
      clearances.push_back(clearance);
    }
    const bool straight_blocked = !path.ok || path.raw_vertices > 2;
    blocked += straight_blocked;
    std::printf(
        "%s{\"ok\": %s, \"straight_blocked\": %s, \"straight_m\": %.2f, \"time_s\": %.4f, \"length_ratio\": %.3f, "
        "\"clearance_m\": %.3f}",
        i ? ", " : "", path.ok ? "true" : "false", straight_blocked ? "true" : "false", (goal - start).norm(),
        path.planning_time_s, ratio, clearance);
  }
  std::printf(
      "], \"success_rate\": %.3f, \"median_time_s\": %.4f, \"max_time_s\": %.4f, \"median_length_ratio\": %.3f, "
      "\"max_length_ratio\": %.3f, \"straight_blocked\": %d, \"median_length_ratio_blocked\": %.3f, "
      "\"smallest_clearance_m\": %.3f, \"radius_m\": %.3f, \"clearance_kept_m\": %.3f}\n",
      pairs ? static_cast<double>(solved) / pairs : 0.0, Median(times),
      times.empty() ? 0.0 : *std::max_element(times.begin(), times.end()), Median(ratios),
      ratios.empty() ? 0.0 : *std::max_element(ratios.begin(), ratios.end()), blocked, Median(blocked_ratios),
      clearances.empty() ? 0.0 : *std::min_element(clearances.begin(), clearances.end()), params.radius_m,
      params.Clearance_m());
  return 0;
}
