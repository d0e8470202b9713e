// What an autopilot interface knows of its vehicle at one step, in our frames and SI units (ENU
// world, FLU body): the ground truth from the engine and the latest reading of each sensor plugin.
// Each protocol turns it into its own packets (px4_mavlink.h, betaflight_packets.h, ardupilot_json.h).
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rotors_gazebo_plugins {

struct VehicleSnapshot {
  double time_s = 0.0;  ///< sim time

  // ground truth of the base link
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();                          ///< [m] ENU
  Eigen::Quaterniond q_WB = Eigen::Quaterniond::Identity();               ///< ENU <- FLU
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();                          ///< [m/s] ENU
  Eigen::Vector3d omega_B = Eigen::Vector3d::Zero();                      ///< [rad/s] FLU
  Eigen::Vector3d specific_force_B = Eigen::Vector3d::Zero();             ///< [m/s^2] FLU, true (R^T (a - g))
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();                          ///< [m/s^2] ENU, true acceleration
  Eigen::Vector3d latitude_longitude_altitude = Eigen::Vector3d::Zero();  ///< [deg, deg, m] of p_W

  // the IMU plugin (imuSubTopic; each sensor below: its reading on the vehicle bus, sensor_feeds.h)
  bool has_imu = false;
  uint64_t imu_count = 0;
  Eigen::Vector3d gyro_B = Eigen::Vector3d::Zero();   ///< [rad/s] FLU
  Eigen::Vector3d accel_B = Eigen::Vector3d::Zero();  ///< [m/s^2] FLU, specific force

  // the magnetometer plugin (magSubTopic)
  bool has_mag = false;
  uint64_t mag_count = 0;
  Eigen::Vector3d mag_B_T = Eigen::Vector3d::Zero();  ///< [T] FLU

  // the pressure plugin (baroSubTopic)
  bool has_baro = false;
  uint64_t baro_count = 0;
  double pressure_Pa = 101325.0;

  // the airspeed plugin (airspeedSubTopic): its wind-relative reading and a pitot's differential pressure
  bool has_diff_pressure = false;
  uint64_t diff_pressure_count = 0;
  double diff_pressure_Pa = 0.0;
  double airspeed_m_s = 0.0;  ///< the norm of the sensor's reading (along its pitot axis, or 3-axis)

  // the GPS plugin (gpsSubTopic, groundSpeedSubTopic)
  bool has_gps = false;
  uint64_t gps_count = 0;
  Eigen::Vector3d gps_latitude_longitude_altitude = Eigen::Vector3d::Zero();  ///< [deg, deg, m]
  Eigen::Vector3d gps_velocity_W = Eigen::Vector3d::Zero();                   ///< [m/s] ENU
  double gps_hor_std_m = 0.0, gps_ver_std_m = 0.0;

  // a range sensor (lidarSubTopic: the lidar or range plugin's reading on the vehicle bus)
  bool has_range = false;
  uint64_t range_count = 0;
  double range_m = 0.0, range_min_m = 0.0, range_max_m = 0.0;

  // the optical flow plugin (opticalFlowSubTopic, mavros_msgs/OpticalFlowRad)
  bool has_flow = false;
  uint64_t flow_count = 0;
  uint32_t flow_integration_time_us = 0;
  Eigen::Vector2d flow_integrated_xy_rad = Eigen::Vector2d::Zero();
  Eigen::Vector3d flow_integrated_gyro_rad = Eigen::Vector3d::Zero();
  double flow_distance_m = 0.0;
  int flow_quality = 0;
};

}  // namespace rotors_gazebo_plugins
