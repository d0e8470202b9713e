#!/usr/bin/env python3
"""The hovering example with the VI-sensor model on ROS 2, with mav_hovering_example_with_vi_sensor.launch's
arguments in roslaunch's form (docs/ros2.md): mav_hovering_example.py's, with the firefly carrying the
VI-sensor (its stereo pair, IMU, and with enable_vi_depth:=true its depth camera; enable_dvs:=true its
event camera), every topic of it on ROS 2; with enable_logging:=true its bag records the VI-sensor's IMU as well.

    source scripts/ros2_env.bash
    python rotors_gazebo_compat/rotors_ros2/mav_hovering_example_with_vi_sensor.py sensor_realism:=true
"""

import sys

from mav_hovering_example import main

# the launch file's arguments for the vehicle's xacro, with their defaults
VI_SENSOR_ARGUMENTS = {
    "sensor_realism": "false",
    "mass_scale": "1",
    "motor_constant_scale": "1",
    "enable_vi_depth": "false",
    "enable_vi_ground_truth_depth": "false",
    "enable_dvs": "false",
}

if __name__ == "__main__":
    # its bag records the VI-sensor's IMU too
    sys.exit(main(sys.argv[1:], model="mav_with_vi_sensor", xacro_arguments=VI_SENSOR_ARGUMENTS, recorded_extra=("vi_sensor/imu",)))
