// libgazebo_ros_openni_kinect.so (gazebo_ros' Kinect plugin): exact depth, gazebo_ros' topic
// defaults (depth/image_raw, depth/camera_info, depth/points). RotorS' VI-sensor names its depth
// image topic "depth/disparity"; it carries depth in metres there too, as in Gazebo.
#include "depth_camera_ros_plugin.h"

RSIM_REGISTER_SENSOR_PLUGIN(rotors_gazebo_plugins::DepthCameraRosPlugin)
