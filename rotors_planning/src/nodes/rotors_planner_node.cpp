// rotors_planner_node: plans collision-free trajectories for one MAV (run it in the MAV's
// namespace). Goals come from ~waypoint_file (RotorS' format, flown in order) or from `goal`
// (geometry_msgs/PoseStamped, replaces the rest). The map: ~map_source "world" (the simulator's
// world/get_octomap in the box ~map_min-~map_max), "file" (~map_file, a .bt or .ot) or "topic"
// (octomap_binary of a mapping node: the map being built; unknown space is free, and a trajectory
// that the new map shows in collision is replanned from where the MAV is).
// Out: command/trajectory (MultiDOFJointTrajectory with velocity and acceleration feed-forward for
// the Lee controller), planner/goal (PoseStamped, each goal when its leg starts), planner/path.
// A goal that cannot be flown (inside an obstacle, outside the map, unreachable, no map) is one
// line of error; the MAV keeps hovering where it is.
// Threads: odometry, goals and maps arrive on roscpp's global queue (ros::spin in main); planning
// runs in the timer on its own queue and thread, so a long plan does not hold back the odometry.
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <octomap_msgs/Octomap.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <rotors_comm/Octomap.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "mesh_radius.h"
#include "octomap_ros.h"
#include "rotors_planning/occupancy_grid.h"
#include "rotors_planning/path_planner.h"
#include "rotors_planning/trajectory.h"
#include "rotors_planning/vehicle_radius.h"
#include "rotors_planning/waypoint_file.h"

namespace rotors_planning {
namespace {

double Yaw(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

std::string Text(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

}  // namespace

class PlannerNode {
 public:
  PlannerNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh) {
    PathPlannerParams params;
    pnh.param("robot_radius", params.radius_m, -1.0);
    if (params.radius_m <= 0.0) {
      std::string urdf;
      if (!nh_.getParam("robot_description", urdf)) {
        throw std::runtime_error("no ~robot_radius and no " + nh_.resolveName("robot_description") +
                                 " to take the radius from; set ~robot_radius [m]");
      }
      params.radius_m = VehicleRadius_m(urdf, MeshRadius_m);
    }
    pnh.param("margin", params.margin_m, params.margin_m);
    pnh.param("planning_time", params.planning_time_s, params.planning_time_s);
    int seed = 1;
    pnh.param("seed", seed, seed);
    params.seed = static_cast<unsigned>(seed);
    planner_ = std::make_unique<PathPlanner>(params);
    pnh.param("max_speed", limits_.max_speed_mps, limits_.max_speed_mps);
    pnh.param("max_acceleration", limits_.max_acceleration_mps2, limits_.max_acceleration_mps2);
    pnh.param("max_yaw_rate", limits_.max_yaw_rate_radps, limits_.max_yaw_rate_radps);
    if (const std::string why = limits_.Validate(); !why.empty()) throw std::runtime_error(why);
    pnh.param("sample_dt", sample_dt_s_, 0.05);
    pnh.param("start_delay", start_delay_s_, 5.0);
    pnh.param<std::string>("frame_id", frame_id_, "world");
    map_min_W_ = VectorParam(pnh, "map_min", Eigen::Vector3d(-20, -20, 0.5));
    map_max_W_ = VectorParam(pnh, "map_max", Eigen::Vector3d(20, 20, 10));
    std::string waypoint_file;
    if (pnh.getParam("waypoint_file", waypoint_file)) {
      for (const Waypoint& w : ReadWaypointFile(waypoint_file)) goals_.push_back(w);
      ROS_INFO("[planner] %zu waypoints from %s", goals_.size(), waypoint_file.c_str());
    }

    trajectory_pub_ = nh_.advertise<trajectory_msgs::MultiDOFJointTrajectory>("command/trajectory", 1);
    goal_pub_ = nh_.advertise<geometry_msgs::PoseStamped>("planner/goal", 10, /*latch=*/true);
    path_pub_ = nh_.advertise<nav_msgs::Path>("planner/path", 1, /*latch=*/true);
    odometry_sub_ = nh_.subscribe("odometry", 1, &PlannerNode::OnOdometry, this);
    goal_sub_ = nh_.subscribe("goal", 1, &PlannerNode::OnGoal, this);
    LoadMap(pnh);
    ROS_INFO("[planner] radius %.3f m + margin %.2f m; limits %.2f m/s, %.2f m/s^2; map box %s - %s from %s",
             params.radius_m, params.margin_m, limits_.max_speed_mps, limits_.max_acceleration_mps2,
             Text(map_min_W_).c_str(), Text(map_max_W_).c_str(), map_source_.c_str());
    ros::NodeHandle planning_nh(nh_);
    planning_nh.setCallbackQueue(&planning_queue_);
    timer_ = planning_nh.createTimer(ros::Duration(0.1), &PlannerNode::OnTimer, this);
    planning_spinner_.start();
  }

  ~PlannerNode() {
    timer_.stop();
    planning_spinner_.stop();
  }

 private:
  void LoadMap(const ros::NodeHandle& pnh) {
    pnh.param<std::string>("map_source", map_source_, "world");
    if (map_source_ == "topic") {
      map_sub_ = nh_.subscribe("octomap_binary", 1, &PlannerNode::OnMap, this);
    } else if (map_source_ == "file") {
      std::string path;
      pnh.param<std::string>("map_file", path, "");
      std::unique_ptr<octomap::AbstractOcTree> tree(octomap::AbstractOcTree::read(path));
      auto* octree = dynamic_cast<octomap::OcTree*>(tree.get());
      if (!octree) {
        no_map_reason_ = "map file '" + path + "' does not exist or holds no OcTree (~map_file)";
        ROS_ERROR("[planner] %s", no_map_reason_.c_str());
        return;
      }
      SetMap(*octree);
    } else if (map_source_ == "world") {
      std::string service;
      double leaf_m = 0.25;
      pnh.param<std::string>("map_service", service, "/world/get_octomap");
      pnh.param("map_resolution", leaf_m, leaf_m);
      rotors_comm::Octomap srv;
      const Eigen::Vector3d center = 0.5 * (map_min_W_ + map_max_W_), lengths = map_max_W_ - map_min_W_;
      srv.request.bounding_box_origin.x = center.x();
      srv.request.bounding_box_origin.y = center.y();
      srv.request.bounding_box_origin.z = center.z();
      srv.request.bounding_box_lengths.x = lengths.x();
      srv.request.bounding_box_lengths.y = lengths.y();
      srv.request.bounding_box_lengths.z = lengths.z();
      srv.request.leaf_size = leaf_m;
      srv.request.publish_octomap = true;  // rviz shows what the planner plans in (world/octomap_markers)
      if (!ros::service::waitForService(service, ros::Duration(60.0)) || !ros::service::call(service, srv)) {
        no_map_reason_ = "the map service " + service + " did not answer";
        ROS_ERROR("[planner] %s", no_map_reason_.c_str());
        return;
      }
      SetMap(*FromMsg(srv.response.map));
    } else {
      throw std::runtime_error("~map_source = '" + map_source_ + "' is none of world, file, topic");
    }
  }

  void SetMap(const octomap::OcTree& tree) {
    grid_ = std::make_unique<OccupancyGrid>(tree, map_min_W_, map_max_W_);
    ROS_INFO_ONCE("[planner] map: %zu occupied cells of %.2f m", grid_->OccupiedCount(), grid_->Resolution_m());
  }

  void OnMap(const octomap_msgs::OctomapConstPtr& msg) {
    try {
      std::unique_ptr<octomap::OcTree> map = FromMsg(*msg);
      std::lock_guard<std::mutex> lock(inputs_mutex_);
      pending_map_ = std::move(map);
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "[planner] map on %s ignored: %s", map_sub_.getTopic().c_str(), e.what());
    }
  }

  void OnOdometry(const nav_msgs::OdometryConstPtr& msg) {
    const auto& p = msg->pose.pose.position;
    std::lock_guard<std::mutex> lock(inputs_mutex_);
    p_W_ = Eigen::Vector3d(p.x, p.y, p.z);
    yaw_rad_ = Yaw(msg->pose.pose.orientation);
    if (!start_time_) start_time_ = ros::Time::now() + ros::Duration(start_delay_s_);
  }

  void OnGoal(const geometry_msgs::PoseStampedConstPtr& msg) {
    Waypoint w;
    w.p_W = Eigen::Vector3d(msg->pose.position.x, msg->pose.position.y, msg->pose.position.z);
    w.yaw_rad = Yaw(msg->pose.orientation);
    std::lock_guard<std::mutex> lock(inputs_mutex_);
    goals_.assign(1, w);
    next_goal_time_ = ros::Time(0);
  }

  /// The planning thread: takes the inputs under the lock, then maps and plans without it.
  void OnTimer(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    std::unique_ptr<octomap::OcTree> map;
    std::optional<Waypoint> goal;
    {
      std::lock_guard<std::mutex> lock(inputs_mutex_);
      if (pending_map_ && (now - map_time_).toSec() >= 0.5) {
        map = std::move(pending_map_);
        map_time_ = now;
      }
      const bool waiting_for_first_map = !grid_ && !map && map_source_ == "topic";
      if (start_time_ && now >= *start_time_ && !goals_.empty() && now >= next_goal_time_ && !waiting_for_first_map) {
        goal = goals_.front();
        goals_.pop_front();
      }
      here_ = {p_W_, yaw_rad_};
    }
    if (map) {
      SetMap(*map);
      CheckAhead(now);
    }
    if (goal) StartLeg(*goal, now);
  }

  /// Plans from where the MAV is to the goal and sends the trajectory; on failure it stays put.
  bool StartLeg(const Waypoint& goal, const ros::Time& now) {
    ++legs_;
    SetNextGoalTime(now + ros::Duration(goal.wait_time_s));
    if (!grid_) {
      ROS_ERROR("[planner] goal %s refused: no map (%s); hovering", Text(goal.p_W).c_str(),
                no_map_reason_.empty() ? "none received yet" : no_map_reason_.c_str());
      return false;
    }
    const PlannedPath path = planner_->Plan(*grid_, here_.p_W, goal.p_W);
    if (!path.ok) {
      ROS_ERROR("[planner] goal %s refused: %s; hovering", Text(goal.p_W).c_str(), path.reason.c_str());
      return false;
    }
    leg_ = Leg{goal, RestToRestTrajectory(path.p_W, here_.yaw_rad, goal.yaw_rad, limits_), now};
    const double duration_s = leg_->trajectory.Duration_s();
    {
      std::lock_guard<std::mutex> lock(inputs_mutex_);
      if (now + ros::Duration(duration_s) > next_goal_time_) next_goal_time_ = now + ros::Duration(duration_s);
    }
    ROS_INFO("[planner] leg %d to %s: %zu vertices (RRT-Connect %zu) in %.3f s, %.1f s of flight, %d replans so far",
             legs_, Text(goal.p_W).c_str(), path.p_W.size(), path.raw_vertices, path.planning_time_s, duration_s,
             replans_);
    Send(path, now);
    return true;
  }

  void Send(const PlannedPath& path, const ros::Time& now) {
    trajectory_msgs::MultiDOFJointTrajectory msg;
    msg.header.stamp = now;
    msg.header.frame_id = frame_id_;
    msg.joint_names.push_back("base_link");
    const RestToRestTrajectory& trajectory = leg_->trajectory;
    for (double t = 0.0;; t += sample_dt_s_) {
      const TrajectorySample s = trajectory.Sample(t);
      trajectory_msgs::MultiDOFJointTrajectoryPoint point;
      geometry_msgs::Transform X;
      X.translation.x = s.p_W.x();
      X.translation.y = s.p_W.y();
      X.translation.z = s.p_W.z();
      X.rotation.z = std::sin(0.5 * s.yaw_rad);
      X.rotation.w = std::cos(0.5 * s.yaw_rad);
      geometry_msgs::Twist v;
      v.linear.x = s.v_W.x();
      v.linear.y = s.v_W.y();
      v.linear.z = s.v_W.z();
      v.angular.z = s.yaw_rate_radps;
      geometry_msgs::Twist a;
      a.linear.x = s.a_W.x();
      a.linear.y = s.a_W.y();
      a.linear.z = s.a_W.z();
      point.transforms.push_back(X);
      point.velocities.push_back(v);
      point.accelerations.push_back(a);
      point.time_from_start = ros::Duration(std::min(t, trajectory.Duration_s()));
      msg.points.push_back(point);
      if (t >= trajectory.Duration_s()) break;
    }
    trajectory_pub_.publish(msg);
    geometry_msgs::PoseStamped goal;
    goal.header = msg.header;
    goal.pose.position.x = leg_->goal.p_W.x();
    goal.pose.position.y = leg_->goal.p_W.y();
    goal.pose.position.z = leg_->goal.p_W.z();
    goal.pose.orientation.z = std::sin(0.5 * leg_->goal.yaw_rad);
    goal.pose.orientation.w = std::cos(0.5 * leg_->goal.yaw_rad);
    goal_pub_.publish(goal);
    nav_msgs::Path drawn;
    drawn.header = msg.header;
    for (const Eigen::Vector3d& p : path.p_W) {
      geometry_msgs::PoseStamped pose;
      pose.header = msg.header;
      pose.pose.position.x = p.x();
      pose.pose.position.y = p.y();
      pose.pose.position.z = p.z();
      pose.pose.orientation.w = 1.0;
      drawn.poses.push_back(pose);
    }
    path_pub_.publish(drawn);
  }

  /// With a map being built: a trajectory that now passes closer than the radius plus half the
  /// margin to an occupied cell is replanned from where the MAV is.
  void CheckAhead(const ros::Time& now) {
    if (!leg_) return;
    const double t0 = (now - leg_->start).toSec(), end = leg_->trajectory.Duration_s();
    if (t0 >= end) return;
    const PathPlannerParams& params = planner_->Params();
    const double needed_m = params.radius_m + 0.5 * params.margin_m;
    for (double t = t0; t <= end + 1e-9; t += 0.05) {
      const Eigen::Vector3d p = leg_->trajectory.Sample(t).p_W;
      if (!grid_->Contains(p)) continue;
      const double clearance = grid_->Clearance_m(p, needed_m);
      if (clearance >= needed_m) continue;
      ++replans_;
      ROS_WARN("[planner] replan %d: the trajectory ahead passes %.2f m from an obstacle at %s", replans_, clearance,
               Text(p).c_str());
      const Waypoint goal = leg_->goal;
      leg_.reset();
      if (!StartLeg(goal, now)) Hover(now);
      return;
    }
  }

  void SetNextGoalTime(const ros::Time& t) {
    std::lock_guard<std::mutex> lock(inputs_mutex_);
    next_goal_time_ = t;
  }

  /// Holds the position the MAV is at.
  void Hover(const ros::Time& now) {
    PlannedPath here;
    here.p_W = {here_.p_W, here_.p_W};
    leg_ = Leg{Waypoint{0.0, here_.p_W, here_.yaw_rad},
               RestToRestTrajectory(here.p_W, here_.yaw_rad, here_.yaw_rad, limits_), now};
    Send(here, now);
  }

  struct Leg {
    Waypoint goal;
    RestToRestTrajectory trajectory;
    ros::Time start;
  };
  struct Pose {
    Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
    double yaw_rad = 0.0;
  };

  ros::NodeHandle nh_;
  std::unique_ptr<PathPlanner> planner_;
  TrajectoryLimits limits_;
  double sample_dt_s_ = 0.05, start_delay_s_ = 5.0;
  std::string frame_id_, map_source_, no_map_reason_;
  Eigen::Vector3d map_min_W_, map_max_W_;
  // the planning thread's own
  std::unique_ptr<OccupancyGrid> grid_;
  std::optional<Leg> leg_;
  Pose here_;  ///< where the MAV was when this timer call began
  int replans_ = 0, legs_ = 0;
  // shared with the callbacks of the global queue
  std::mutex inputs_mutex_;
  std::unique_ptr<octomap::OcTree> pending_map_;
  ros::Time map_time_;
  Eigen::Vector3d p_W_ = Eigen::Vector3d::Zero();
  double yaw_rad_ = 0.0;
  std::optional<ros::Time> start_time_;
  std::deque<Waypoint> goals_;
  ros::Time next_goal_time_;
  ros::Publisher trajectory_pub_, goal_pub_, path_pub_;
  ros::Subscriber odometry_sub_, goal_sub_, map_sub_;
  ros::CallbackQueue planning_queue_;
  ros::AsyncSpinner planning_spinner_{1, &planning_queue_};
  ros::Timer timer_;
};

}  // namespace rotors_planning

int main(int argc, char** argv) {
  ros::init(argc, argv, "rotors_planner_node");
  try {
    rotors_planning::PlannerNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("[planner] %s", e.what());
    return 1;
  }
  return 0;
}
