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
# setuptools' distutils shim (installed into the venv) makes every `import distutils` load setuptools'
# own copy: 0.5 s more for each roslaunch and each xacro run. The standard library's is enough.
export SETUPTOOLS_USE_DISTUTILS=stdlib
