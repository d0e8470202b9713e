#!/usr/bin/env bash
# make ros2-demo: the book's hovering example on ROS 2, headless (docs/ros2.md). The ROS 2 front
# end flies the firefly for ~25 s of simulated time (as fast as it can, in lockstep with its
# controller) on a loopback-only graph, an rclpy recorder writes a ROS 2 bag (MCAP) under
# build/ros2-demo, and RotorS' hovering_eval.py scores it, as `make demo` does on ROS 1.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$root/build/ros2-demo"
rm -rf "$out" && mkdir -p "$out"
sim_seconds=${DEMO_SIM_SECONDS:-25}
echo "[ros2-demo] python rotors_gazebo_compat/rotors_ros2/mav_hovering_example.py enable_logging:=true real_time_factor:=0 sim_seconds:=$sim_seconds"
(
  set +u
  # shellcheck disable=SC1091
  source "$root/scripts/ros2_env.bash"
  set -u
  export ROS_HOME="$out" ROS_LOG_DIR="$out/log"
  python "$root/rotors_gazebo_compat/rotors_ros2/mav_hovering_example.py" enable_logging:=true real_time_factor:=0 \
    sim_seconds:="$sim_seconds" > "$out/ros2.log" 2>&1
) || { echo "[ros2-demo] the flight failed; see $out/ros2.log" >&2; tail -n 20 "$out/ros2.log" >&2; exit 1; }
grep -E "^rosbag2_record|simulated" "$out/ros2.log" | sed 's/^/[ros2-demo] /'
bag=$(find "$out" -maxdepth 2 -name metadata.yaml -printf '%h\n' | head -n1)
if [ -z "$bag" ]; then
  echo "[ros2-demo] no bag was written; see $out/ros2.log" >&2
  exit 1
fi
set +u
# shellcheck disable=SC1091
source "$root/scripts/env.bash"
set -u
echo "[ros2-demo] bag: $bag"
echo "[ros2-demo] rosrun rotors_evaluation hovering_eval.py -b $bag --save_plots True --mav_name firefly"
rosrun rotors_evaluation hovering_eval.py -b "$bag" --save_plots True --plot False --mav_name firefly \
  --plot_dir "$out/plots" --json "$out/hovering_eval.json"
echo "[ros2-demo] plots in $out/plots, summary in $out/hovering_eval.json"
