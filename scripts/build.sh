#!/usr/bin/env bash
# Assembles the catkin workspace build/ws (links to every package folder of this repository)
# and builds it with catkin_make. The root package.xml is the rotors_simulator metapackage, which
# stops catkin from crawling sub-folders, hence the link farm.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
ws="$root/build/ws"
export PATH="$root/build/venv/bin:$PATH"
mkdir -p "$ws/src"
# Every folder holding a package.xml (except build/) becomes a link in build/ws/src; ROS 2's
# interface packages (ament_cmake, built by scripts/setup_ros2.sh) are not catkin's.
find "$ws/src" -maxdepth 1 -type l -delete
while IFS= read -r manifest; do
  grep -q "<build_type>ament_cmake</build_type>" "$manifest" && continue
  dir="$(dirname "$manifest")"
  name="$(sed -n 's:.*<name>\(.*\)</name>.*:\1:p' "$manifest" | head -n1)"
  ln -sfn "$dir" "$ws/src/$name"
done < <(find "$root" -path "$root/build" -prune -o -name package.xml -print | sort)
cd "$ws"
args=(-DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DPYTHON_EXECUTABLE="$root/build/venv/bin/python3")
# ROTORS_WERROR=ON (set by .ci/run) turns every compiler warning into an error; unset, the
# workspace keeps what it was configured with (a change recompiles everything)
if [ -n "${ROTORS_WERROR:-}" ]; then args+=(-DROTORS_WERROR="$ROTORS_WERROR"); fi
jobs="-j$(nproc)"
if [ ! -f "$ws/build/CMakeCache.txt" ]; then
  # On a fresh workspace CMake must run twice, or Python tests miss generated messages. The first
  # pass is logged; when it fails, its errors are shown and the build stops.
  echo "[build] fresh workspace: first pass (log: $ws/first_pass.log)"
  if ! catkin_make "${args[@]}" "$jobs" > "$ws/first_pass.log" 2>&1; then
    grep -E -B2 -A6 "error|Error" "$ws/first_pass.log" | tail -n 60 >&2 || tail -n 60 "$ws/first_pass.log" >&2
    echo "[build] the first pass failed; the whole log is $ws/first_pass.log" >&2
    exit 1
  fi
fi
catkin_make "${args[@]}" "$jobs" "$@"
