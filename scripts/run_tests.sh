#!/usr/bin/env bash
# Builds the C++ tests and runs the whole suite (C++ gtests, Python unit and ROS integration tests)
# in one pytest run, so there is one summary line.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
export PATH="$root/build/venv/bin:$PATH"
(cd "$root/build/ws" && catkin_make tests -j"$(nproc)" >/dev/null) || {
  echo "building the tests failed; rerun: cd build/ws && catkin_make tests" >&2; exit 1; }
# shellcheck disable=SC1091
set +u
source "$root/scripts/env.bash"
set -u
unset DISPLAY
cd "$root"
if [ $# -eq 0 ]; then set -- test rotors_gazebo_compat/rotors_evaluation/test; fi
exec python -m pytest -q -p no:cacheprovider "$@"
