# Source this file: `source scripts/env.bash` gives a shell in which roslaunch, rosrun, rostopic,
# rosbag and rviz see every package of this repository (after `make build`).
_rotors_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ ! -f "$_rotors_root/build/ws/devel/setup.bash" ]; then
  echo "rotors_simulator: not built yet; run 'make build' in $_rotors_root first" >&2
else
  # shellcheck disable=SC1091
  source "$_rotors_root/build/ws/devel/setup.bash"
  export PATH="$_rotors_root/build/venv/bin:$PATH"
  export ROTORS_SIM_ROOT="$_rotors_root"
fi
unset _rotors_root
