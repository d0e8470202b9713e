# Source this file: `source scripts/ros2_env.bash` gives a shell for ROS 2 (after `make build` and
# `make ros2-setup`): `python` is build/ros2-venv's (rclpy, PyPI's Jazzy wheels), the graph stays on
# the loopback interface (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a Fast DDS profile bound to lo),
# and ROS 1's environment is kept aside (ROTORS_ROS1_*) for the world's process the ROS 2 front end
# starts (rotors_sim runs on ROS 1's Python packages, whose module names ROS 2's share).
_rotors_ros2_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck disable=SC1091
source "$_rotors_ros2_root/scripts/env.bash"
if [ ! -x "$_rotors_ros2_root/build/ros2-venv/bin/python" ]; then
  echo "rotors_simulator: no ROS 2 venv yet; run 'make ros2-setup' in $_rotors_ros2_root first" >&2
fi
export ROTORS_ROS1_PYTHONPATH="${PYTHONPATH:-}" ROTORS_ROS1_LD_LIBRARY_PATH="${LD_LIBRARY_PATH:-}"
export ROTORS_ROS1_PYTHON="$_rotors_ros2_root/build/venv/bin/python"
unset PYTHONPATH
export PATH="$_rotors_ros2_root/build/ros2-venv/bin:$PATH"
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
export FASTRTPS_DEFAULT_PROFILES_FILE="$_rotors_ros2_root/rotors_gazebo_compat/rotors_ros2/loopback_only.xml"
unset _rotors_ros2_root
