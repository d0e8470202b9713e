// rotors_mapping_node: the role of octomap_server, with OctoMap's own sensor model. Inserts every
// cloud on `cloud_in` (sensor_msgs/PointCloud2) at the sensor's pose in `frame_id` from TF;
// publishes the map (latched) on octomap_binary and octomap_full and the occupied cells for rviz on
// occupied_cells_vis_array; serves octomap_binary and octomap_full (octomap_msgs/GetOctomap),
// ~reset (std_srvs/Empty) and ~save_map (std_srvs/Trigger, writes ~save_path as .bt).
// Private parameters as octomap_server names them: resolution, frame_id, sensor_model/max_range,
// sensor_model/hit, sensor_model/miss, sensor_model/min, sensor_model/max; ours: save_path.
#include <algorithm>
#include <memory>
#include <string>

#include <Eigen/Geometry>
#include <octomap_msgs/GetOctomap.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <std_srvs/Empty.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_listener.h>

#include "octomap_ros.h"
#include "rotors_planning/map_builder.h"

namespace rotors_planning {

class MappingNode {
 public:
  MappingNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), tf_listener_(tf_buffer_) {
    MapBuilderParams params;
    pnh.param("resolution", params.resolution_m, params.resolution_m);
    pnh.param("sensor_model/max_range", params.max_range_m, params.max_range_m);
    pnh.param("sensor_model/hit", params.prob_hit, params.prob_hit);
    pnh.param("sensor_model/miss", params.prob_miss, params.prob_miss);
    pnh.param("sensor_model/min", params.clamping_min, params.clamping_min);
    pnh.param("sensor_model/max", params.clamping_max, params.clamping_max);
    pnh.param<std::string>("frame_id", frame_id_, "world");
    pnh.param<std::string>("save_path", save_path_, "");
    builder_ = std::make_unique<MapBuilder>(params);  // throws with the bad parameter's name
    binary_pub_ = nh_.advertise<octomap_msgs::Octomap>("octomap_binary", 1, /*latch=*/true);
    full_pub_ = nh_.advertise<octomap_msgs::Octomap>("octomap_full", 1, /*latch=*/true);
    markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("occupied_cells_vis_array", 1, /*latch=*/true);
    cloud_sub_ = nh_.subscribe("cloud_in", 1, &MappingNode::OnCloud, this);
    binary_srv_ = nh_.advertiseService("octomap_binary", &MappingNode::OnGetBinary, this);
    full_srv_ = nh_.advertiseService("octomap_full", &MappingNode::OnGetFull, this);
    reset_srv_ = pnh.advertiseService("reset", &MappingNode::OnReset, this);
    save_srv_ = pnh.advertiseService("save_map", &MappingNode::OnSave, this);
    ROS_INFO(
        "[mapping] %.3f m leaves in '%s', max range %.1f m, hit %.2f miss %.2f, clamping %.2f-%.2f; listening on %s",
        params.resolution_m, frame_id_.c_str(), params.max_range_m, params.prob_hit, params.prob_miss,
        params.clamping_min, params.clamping_max, cloud_sub_.getTopic().c_str());
  }

  ~MappingNode() {
    if (!save_path_.empty()) Save();
  }

 private:
  /// "" or why a cloud cannot be read: its data must hold height rows of row_step bytes, each of
  /// width points of point_step bytes (a malformed header would make the iterators read past it).
  static std::string CloudShapeProblem(const sensor_msgs::PointCloud2& c) {
    const uint64_t row_bytes = static_cast<uint64_t>(c.width) * c.point_step;
    if (c.width > 0 && c.height > 0 && c.point_step == 0) return "point_step is 0";
    if (c.row_step < row_bytes)
      return "row_step " + std::to_string(c.row_step) + " < width " + std::to_string(c.width) + " x point_step " +
             std::to_string(c.point_step);
    for (const char* name : {"x", "y", "z"}) {
      const auto field = std::find_if(c.fields.begin(), c.fields.end(), [&](const auto& f) { return f.name == name; });
      if (field == c.fields.end()) return std::string("no field '") + name + "' (x, y, z float32 fields needed)";
      if (field->datatype != sensor_msgs::PointField::FLOAT32 || field->offset + 4u > c.point_step)
        return std::string("field '") + name + "' is not a float32 inside point_step " + std::to_string(c.point_step);
    }
    const uint64_t need = static_cast<uint64_t>(c.row_step) * c.height;
    if (c.data.size() < need)
      return "data holds " + std::to_string(c.data.size()) + " bytes, height x row_step needs " + std::to_string(need);
    return "";
  }

  void OnCloud(const sensor_msgs::PointCloud2ConstPtr& cloud) {
    // tf2 logs every lookup of an empty or '/'-prefixed frame id itself: refuse those here, once in 5 s
    const std::string& frame = cloud->header.frame_id;
    if (frame.empty() || frame.front() == '/') {
      ROS_WARN_THROTTLE(5.0, "[mapping] cloud on %s dropped: header.frame_id '%s' is %s", cloud_sub_.getTopic().c_str(),
                        frame.c_str(), frame.empty() ? "empty" : "not a tf2 frame id (it starts with '/')");
      return;
    }
    geometry_msgs::TransformStamped X_WS;
    try {
      X_WS = tf_buffer_.lookupTransform(frame_id_, cloud->header.frame_id, cloud->header.stamp, ros::Duration(0.5));
    } catch (const tf2::TransformException& e) {
      ROS_WARN_THROTTLE(5.0, "[mapping] cloud dropped: no transform %s <- %s at %.3f s: %s", frame_id_.c_str(),
                        cloud->header.frame_id.c_str(), cloud->header.stamp.toSec(), e.what());
      return;
    }
    const auto& q = X_WS.transform.rotation;
    const auto& t = X_WS.transform.translation;
    const Eigen::Matrix3d R_WS = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
    const Eigen::Vector3d p_WS(t.x, t.y, t.z);
    const std::string malformed = CloudShapeProblem(*cloud);
    if (!malformed.empty()) {
      ROS_ERROR_THROTTLE(5.0, "[mapping] cloud on %s dropped: %s", cloud_sub_.getTopic().c_str(), malformed.c_str());
      return;
    }
    std::vector<Eigen::Vector3d> points_W;
    try {
      points_W.reserve(static_cast<size_t>(cloud->width) * cloud->height);
      sensor_msgs::PointCloud2ConstIterator<float> x(*cloud, "x"), y(*cloud, "y"), z(*cloud, "z");
      for (; x != x.end(); ++x, ++y, ++z) {
        const Eigen::Vector3d p_S(*x, *y, *z);
        if (p_S.allFinite()) points_W.push_back(p_WS + R_WS * p_S);  // NaN: no return (depth cameras)
      }
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(5.0, "[mapping] cloud on %s dropped: %s (x, y, z float32 fields needed)",
                         cloud_sub_.getTopic().c_str(), e.what());
      return;
    }
    builder_->Insert(points_W, p_WS);
    ++clouds_;
    Publish(cloud->header.stamp);
  }

  void Publish(const ros::Time& stamp) {
    const octomap::OcTree& tree = builder_->Tree();
    if (binary_pub_.getNumSubscribers() > 0) {
      octomap_msgs::Octomap msg = ToMsg(tree, frame_id_, true);
      msg.header.stamp = stamp;
      binary_pub_.publish(msg);
    }
    if (full_pub_.getNumSubscribers() > 0) {
      octomap_msgs::Octomap msg = ToMsg(tree, frame_id_, false);
      msg.header.stamp = stamp;
      full_pub_.publish(msg);
    }
    if (markers_pub_.getNumSubscribers() > 0) markers_pub_.publish(OccupiedCells(tree, frame_id_, stamp));
  }

  bool OnGetBinary(octomap_msgs::GetOctomap::Request&, octomap_msgs::GetOctomap::Response& res) {
    res.map = ToMsg(builder_->Tree(), frame_id_, true);
    res.map.header.stamp = ros::Time::now();
    return true;
  }
  bool OnGetFull(octomap_msgs::GetOctomap::Request&, octomap_msgs::GetOctomap::Response& res) {
    res.map = ToMsg(builder_->Tree(), frame_id_, false);
    res.map.header.stamp = ros::Time::now();
    return true;
  }
  bool OnReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
    builder_->Clear();
    Publish(ros::Time::now());
    ROS_INFO("[mapping] map cleared");
    return true;
  }
  bool OnSave(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    res.success = Save();
    res.message =
        res.success ? save_path_ : "cannot write '" + save_path_ + "' (set ~save_path to a writable .bt path)";
    return true;
  }

  bool Save() {
    if (save_path_.empty() || !builder_->Tree().writeBinaryConst(save_path_)) {
      ROS_ERROR_THROTTLE(5.0, "[mapping] cannot write the map to '%s'; set ~save_path to a writable .bt path",
                         save_path_.c_str());  // the service's response says so on every call
      return false;
    }
    ROS_INFO("[mapping] %zu leaves from %zu clouds written to %s", builder_->Tree().getNumLeafNodes(), clouds_,
             save_path_.c_str());
    return true;
  }

  ros::NodeHandle nh_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  std::unique_ptr<MapBuilder> builder_;
  std::string frame_id_, save_path_;
  size_t clouds_ = 0;
  ros::Publisher binary_pub_, full_pub_, markers_pub_;
  ros::Subscriber cloud_sub_;
  ros::ServiceServer binary_srv_, full_srv_, reset_srv_, save_srv_;
};

}  // namespace rotors_planning

int main(int argc, char** argv) {
  ros::init(argc, argv, "rotors_mapping_node");
  try {
    rotors_planning::MappingNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("[mapping] %s", e.what());
    return 1;
  }
  return 0;
}
