#include "rotors_planning/path_planner.h"

#include <chrono>
#include <cmath>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

namespace rotors_planning {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

std::string Text(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(3);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

/// OMPL's seed is one per process and must be set before its first random number generator.
void SeedOmplOnce(unsigned int seed) {
  static std::once_flag once;
  std::call_once(once, [seed] {
    ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
    if (seed != 0) ompl::RNG::setSeed(seed);
  });
}

}  // namespace

std::string PathPlannerParams::Validate() const {
  std::ostringstream why;
  if (!(radius_m > 0.0)) {
    why << "robot_radius = " << radius_m << " must be > 0 m";
  } else if (!(margin_m >= 0.0)) {
    why << "margin = " << margin_m << " must be >= 0 m";
  } else if (!(planning_time_s > 0.0)) {
    why << "planning_time = " << planning_time_s << " must be > 0 s";
  } else if (!(escape_m >= 0.0)) {
    why << "escape distance = " << escape_m << " must be >= 0 m";
  }
  return why.str();
}

PathPlanner::PathPlanner(const PathPlannerParams& params) : params_(params) {
  const std::string why = params.Validate();
  if (!why.empty()) throw std::invalid_argument(why);
  SeedOmplOnce(params.seed);
}

PlannedPath PathPlanner::Plan(const OccupancyGrid& grid, const Eigen::Vector3d& start_W,
                              const Eigen::Vector3d& goal_W) const {
  const auto t0 = std::chrono::steady_clock::now();
  PlannedPath result;
  const double clearance = params_.Clearance_m();
  auto fail = [&](const std::string& why) {
    result.reason = why;
    result.planning_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  };
  if (!start_W.allFinite() || !goal_W.allFinite()) return fail("start or goal is not finite");
  if (!grid.Contains(goal_W)) {
    return fail("goal " + Text(goal_W) + " is outside the map box " + Text(grid.Min_W()) + " - " + Text(grid.Max_W()));
  }
  const double goal_clearance = grid.Clearance_m(goal_W, clearance);
  if (goal_clearance < clearance) {
    std::ostringstream why;
    why << "goal " << Text(goal_W) << " is inside or near an obstacle: " << goal_clearance
        << " m from an occupied cell, " << clearance << " m needed (radius " << params_.radius_m << " + margin "
        << params_.margin_m << ")";
    return fail(why.str());
  }
  std::vector<Eigen::Vector3d> prefix{start_W};
  Eigen::Vector3d from = start_W;
  if (from.z() < grid.Min_W().z() && grid.Contains({from.x(), from.y(), grid.Min_W().z()})) {
    from.z() = grid.Min_W().z();  // on the ground: climb into the box first
    if (!grid.SegmentIsFree(start_W, from, params_.radius_m)) return fail("no room to climb from " + Text(start_W));
    prefix.push_back(from);
  }
  if (!grid.Contains(from)) {
    return fail("start " + Text(from) + " is outside the map box " + Text(grid.Min_W()) + " - " + Text(grid.Max_W()));
  }
  if (!grid.IsFree(from, clearance)) {
    Eigen::Vector3d out;
    if (!Escape(grid, from, &out)) {
      return fail("start " + Text(from) + " is closer than " + std::to_string(clearance) +
                  " m to an obstacle and no free point is within " + std::to_string(params_.escape_m) + " m");
    }
    prefix.push_back(out);
    from = out;
  }
  std::vector<Eigen::Vector3d> path = Search(grid, from, goal_W, &result.raw_vertices);
  if (path.empty()) {
    std::ostringstream why;
    why << "no path from " << Text(from) << " to " << Text(goal_W) << " found in " << params_.planning_time_s
        << " s (unreachable with " << clearance << " m clearance?)";
    return fail(why.str());
  }
  result.p_W = prefix;
  result.p_W.insert(result.p_W.end(), path.begin() + 1, path.end());
  result.ok = true;
  return fail("");
}

std::vector<Eigen::Vector3d> PathPlanner::Search(const OccupancyGrid& grid, const Eigen::Vector3d& a_W,
                                                 const Eigen::Vector3d& b_W, size_t* raw_vertices) const {
  const double clearance = params_.Clearance_m();
  if (grid.SegmentIsFree(a_W, b_W, clearance)) {
    *raw_vertices = 2;
    return {a_W, b_W};
  }
  auto space = std::make_shared<ob::RealVectorStateSpace>(3);
  ob::RealVectorBounds bounds(3);
  for (int i = 0; i < 3; ++i) {
    bounds.setLow(i, grid.Min_W()[i]);
    bounds.setHigh(i, grid.Max_W()[i]);
  }
  space->setBounds(bounds);
  og::SimpleSetup setup(space);
  // states checked every quarter cell along an edge; each with the clearance plus half that step,
  // so every point between two checked states keeps the clearance
  const double step_m = 0.25 * grid.Resolution_m();
  setup.setStateValidityChecker([&grid, clearance, step_m](const ob::State* state) {
    const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    return grid.IsFree({v[0], v[1], v[2]}, clearance + 0.5 * step_m);
  });
  setup.getSpaceInformation()->setStateValidityCheckingResolution(step_m / space->getMaximumExtent());
  setup.setPlanner(std::make_shared<og::RRTConnect>(setup.getSpaceInformation()));
  ob::ScopedState<> start(space), goal(space);
  for (int i = 0; i < 3; ++i) {
    start[i] = a_W[i];
    goal[i] = b_W[i];
  }
  setup.setStartAndGoalStates(start, goal);
  if (setup.solve(params_.planning_time_s) != ob::PlannerStatus::EXACT_SOLUTION) return {};
  og::PathGeometric& solution = setup.getSolutionPath();
  std::vector<Eigen::Vector3d> raw;
  for (const ob::State* state : solution.getStates()) {
    const double* v = state->as<ob::RealVectorStateSpace::StateType>()->values;
    raw.emplace_back(v[0], v[1], v[2]);
  }
  *raw_vertices = raw.size();
  return Shortcut(grid, raw, clearance);
}

bool PathPlanner::Escape(const OccupancyGrid& grid, const Eigen::Vector3d& start_W, Eigen::Vector3d* free_W) const {
  // rings of candidate points (Fibonacci sphere directions), nearest first
  const int kDirections = 64;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (double r = 0.5 * grid.Resolution_m(); r <= params_.escape_m + 1e-9; r += 0.5 * grid.Resolution_m()) {
    for (int i = 0; i < kDirections; ++i) {
      const double z = 1.0 - 2.0 * (i + 0.5) / kDirections, rho = std::sqrt(1.0 - z * z);
      const Eigen::Vector3d p =
          start_W + r * Eigen::Vector3d(rho * std::cos(golden * i), rho * std::sin(golden * i), z);
      if (grid.Contains(p) && grid.IsFree(p, params_.Clearance_m()) && grid.SegmentIsFree(start_W, p, 0.0)) {
        *free_W = p;
        return true;
      }
    }
  }
  return false;
}

std::vector<Eigen::Vector3d> Shortcut(const OccupancyGrid& grid, const std::vector<Eigen::Vector3d>& path_W,
                                      double clearance_m) {
  if (path_W.size() < 3) return path_W;
  std::vector<Eigen::Vector3d> kept{path_W.front()};
  size_t i = 0;
  while (i + 1 < path_W.size()) {
    size_t j = path_W.size() - 1;
    while (j > i + 1 && !grid.SegmentIsFree(path_W[i], path_W[j], clearance_m)) --j;
    kept.push_back(path_W[j]);  // j = i + 1: the planner's own edge, checked by it
    i = j;
  }
  return kept;
}

}  // namespace rotors_planning
