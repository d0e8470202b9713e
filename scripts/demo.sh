#!/usr/bin/env bash
# The book's sections 3.3 and 3.6, headless: fly the hovering example with logging for ~25 s of
# simulated time (lockstep, faster than real time), then evaluate the bag with hovering_eval.py.
# `demo.sh msf` (make demo-msf): section 3.4, hovering on the estimator for ~45 s, then
# hovering_eval.py and estimator_eval.py.
set -euo pipefail
variant=${1:-ideal}
root="$(cd "$(dirname "$0")/.." && pwd)"
set +u
# shellcheck disable=SC1091
source "$root/scripts/env.bash"
set -u
out="$root/build/demo"
launch_file=mav_hovering_example.launch
launch_args=()
eval_args=()
if [ "$variant" = msf ]; then
  out="$root/build/demo_msf"
  launch_file=mav_hovering_example_msf.launch
  launch_args=(random_seed:=3)
fi
rm -rf "$out" && mkdir -p "$out"
export ROS_HOME="$out"
# a master on a port verified to be its own (another run may pick the same free port meanwhile)
read -r port master_pid < <(python3 -m rotors_evaluation.ros_master "$out/rosmaster.log")
export ROS_MASTER_URI="http://127.0.0.1:$port"
unset DISPLAY
sim_seconds=${DEMO_SIM_SECONDS:-25}
if [ "$variant" = msf ]; then
  sim_seconds=${DEMO_SIM_SECONDS:-45}
  eval_args=(--end_time "$sim_seconds")  # the bag goes on while the launch shuts down
fi

echo "[demo] roslaunch rotors_gazebo $launch_file enable_logging:=true gui:=false lockstep:=true real_time_factor:=10 ${launch_args[*]:-}"
roslaunch -p "$port" rotors_gazebo "$launch_file" enable_logging:=true gui:=false \
  lockstep:=true real_time_factor:=10 "${launch_args[@]}" > "$out/roslaunch.log" 2>&1 &
launch_pid=$!
cleanup() {
  kill -INT "$launch_pid" 2>/dev/null || true; wait "$launch_pid" 2>/dev/null || true
  kill -INT "$master_pid" 2>/dev/null || true
}
trap cleanup EXIT

# the simulator comes up within seconds; 120 s is a hang (a crash ends roslaunch earlier)
for _ in $(seq 600); do
  rosnode list 2>/dev/null | grep -qx /gazebo && break
  kill -0 "$launch_pid" 2>/dev/null || { echo "[demo] roslaunch ended early; see $out/roslaunch.log" >&2; tail -n 20 "$out/roslaunch.log" >&2; exit 1; }
  sleep 0.2
done
rosnode list 2>/dev/null | grep -qx /gazebo || { echo "[demo] the simulator did not start within 120 s; see $out/roslaunch.log" >&2; exit 1; }
python3 - "$sim_seconds" "$out" <<'PY'
import sys, time
import rospy
from rosgraph_msgs.msg import Clock
target = float(sys.argv[1])
deadline = time.monotonic() + 300
rospy.init_node("demo_clock_watch", anonymous=True, disable_signals=True)
t = 0.0
while t < target:
    if time.monotonic() > deadline:
        sys.exit(f"[demo] the simulation did not reach {target} s (at {t:.1f} s); see {sys.argv[2]}/roslaunch.log")
    try:
        t = rospy.wait_for_message("/clock", Clock, timeout=5).clock.to_sec()
    except rospy.ROSException:
        pass
print(f"[demo] simulated {t:.1f} s")
PY
cleanup
trap - EXIT
bag=$(ls -t "$out"/*.bag 2>/dev/null | head -n1 || true)
if [ -z "$bag" ]; then
  echo "[demo] no bag was written; see $out/roslaunch.log" >&2
  exit 1
fi
echo "[demo] bag: $bag"
echo "[demo] rosrun rotors_evaluation hovering_eval.py -b $bag --save_plots True --mav_name firefly"
rosrun rotors_evaluation hovering_eval.py -b "$bag" --save_plots True --plot False --mav_name firefly \
  --plot_dir "$out/plots" --json "$out/hovering_eval.json" "${eval_args[@]}"
if [ "$variant" = msf ]; then
  echo "[demo] rosrun rotors_evaluation estimator_eval.py -b $bag --save_plots True --mav_name firefly"
  rosrun rotors_evaluation estimator_eval.py -b "$bag" --save_plots True --plot False --mav_name firefly \
    --plot_dir "$out/plots" --json "$out/estimator_eval.json" "${eval_args[@]}"
fi
echo "[demo] plots in $out/plots, summary in $out/hovering_eval.json"
