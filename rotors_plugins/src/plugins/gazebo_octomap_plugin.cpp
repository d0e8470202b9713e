// World plugin librotors_gazebo_octomap_plugin.so (RotorS' octomap plugin): the service
// world/get_octomap (rotors_comm/Octomap) builds an OcTree of the world's static collision
// geometry in the requested box, writes it as .bt when a filename is given, replies with it and
// the world origin's latitude/longitude/altitude, and publishes it latched on world/octomap when
// asked (and as rviz cubes on <topic>_markers). SDF: <octomapPubTopic>, <octomapServiceName>.
#include <sstream>

#include <octomap/OcTree.h>
#include <octomap_msgs/Octomap.h>
#include <ros/ros.h>
#include <rotors_comm/Octomap.h>

#include "rotors_core/error.h"
#include "rotors_core/geometry/occupancy_mapper.h"
#include "rotors_core/physics/world.h"
#include "rotors_core/plugin.h"
#include "rotors_core/ros/world_markers.h"
#include "rotors_gazebo_plugins/plugin_params.h"
#include "rotors_gazebo_plugins/ros/plugin_ros.h"

namespace rotors_gazebo_plugins {

class GazeboOctomapPlugin : public rotors_sim::WorldPlugin {
 public:
  void Load(rotors_sim::physics::WorldPtr world, sdf::ElementPtr /*sdf*/) override {
    world_ = world;
    std::string topic = "world/octomap", service = "world/get_octomap";
    ReadParam(Params(), "octomapPubTopic", &topic);
    ReadParam(Params(), "octomapServiceName", &service);
    node_ = MakeNode("");
    if (!node_) return;  // no ROS in this process (engine tests)
    publisher_ = node_->advertise<octomap_msgs::Octomap>(topic, 1, /*latch=*/true);
    // rviz has no OctoMap display without octomap_rviz_plugins: the same map as cubes
    markers_publisher_ = node_->advertise<visualization_msgs::Marker>(topic + "_markers", 1, /*latch=*/true);
    server_ = node_->advertiseService(service, &GazeboOctomapPlugin::OnGetOctomap, this);
  }

 private:
  bool OnGetOctomap(rotors_comm::Octomap::Request& req, rotors_comm::Octomap::Response& res) {
    rotors_sim::geometry::OccupancyRequest request;
    request.center_W = {req.bounding_box_origin.x, req.bounding_box_origin.y, req.bounding_box_origin.z};
    request.lengths_m = {req.bounding_box_lengths.x, req.bounding_box_lengths.y, req.bounding_box_lengths.z};
    request.leaf_size_m = req.leaf_size;
    std::unique_ptr<octomap::OcTree> tree;
    try {
      tree = rotors_sim::geometry::BuildOccupancy(*world_, request);
    } catch (const std::exception& e) {
      ROS_ERROR_STREAM("world/get_octomap: " << e.what());
      return false;
    }
    if (!req.filename.empty() && !tree->writeBinary(req.filename)) {
      ROS_ERROR_STREAM("world/get_octomap: cannot write '" << req.filename << "'");
      return false;
    }
    res.map.header.frame_id = "world";
    res.map.header.stamp = ToRos(world_->SimTime());
    res.map.binary = true;
    res.map.id = tree->getTreeType();
    res.map.resolution = tree->getResolution();
    std::stringstream data;
    tree->writeBinaryData(data);
    const std::string bytes = data.str();
    res.map.data.assign(bytes.begin(), bytes.end());
    const auto& origin = world_->Origin();
    res.origin_latitude = origin.latitude_deg;
    res.origin_longitude = origin.longitude_deg;
    res.origin_altitude = origin.elevation_m;
    ROS_INFO_STREAM("world/get_octomap: " << tree->getNumLeafNodes() << " leaves at " << tree->getResolution() << " m"
                                          << (req.filename.empty() ? "" : ", written to " + req.filename));
    if (req.publish_octomap) {
      publisher_.publish(res.map);
      markers_publisher_.publish(rotors_sim::OcTreeCubes(*tree, "world", "octomap"));
    }
    return true;
  }

  rotors_sim::physics::WorldPtr world_;
  std::shared_ptr<ros::NodeHandle> node_;
  ros::Publisher publisher_, markers_publisher_;
  ros::ServiceServer server_;
};

RSIM_REGISTER_WORLD_PLUGIN(GazeboOctomapPlugin)

}  // namespace rotors_gazebo_plugins
