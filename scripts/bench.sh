#!/usr/bin/env bash
# make bench: engine and closed-loop figures on this machine (see README, Performance).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
set +u
# shellcheck disable=SC1091
source "$root/scripts/env.bash"
set -u
# the benchmark executables are not part of every build (EXCLUDE_FROM_ALL)
make -C "$root/build/ws/build" -j"$(nproc)" rotors_camera_bench rotors_ray_bench rotors_engine_bench msf_ekf_bench \
  rotors_planning_bench > /dev/null
exec python3 "$root/scripts/bench.py" "$@"
