#!/usr/bin/env bash
# Builds the C++ tests and runs the suite (C++ gtests, Python unit and ROS integration tests) in one
# pytest run, so there is one summary line. The tier comes from ROTORS_TEST_TIER: quick (make test:
# every test but those marked long), long (make test-long: only those) or all (make test-all).
# Arguments, when given, replace the test paths (and the tier's selection); they run in one process.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
export PATH="$root/build/venv/bin:$PATH"
# the gtest binaries are built when the run includes test_cpp_units.py (which runs them): every run
# but one naming other test files (make test T=test/test_x.py)
needs_gtests=1
if [ $# -gt 0 ] && ! printf '%s\n' "$@" | grep -qE '(^test/?$|test_cpp_units|rotors_evaluation/test)'; then needs_gtests=0; fi
if [ "$needs_gtests" = 1 ]; then
  (cd "$root/build/ws" && catkin_make tests -j"$(nproc)" >/dev/null) || {
    echo "building the tests failed; rerun: cd build/ws && catkin_make tests" >&2; exit 1; }
fi
# shellcheck disable=SC1091
set +u
source "$root/scripts/env.bash"
set -u
unset DISPLAY
cd "$root"
if [ $# -eq 0 ]; then
  case "${ROTORS_TEST_TIER:-all}" in
    # two workers (pytest-xdist): each test waits a good part of its time on ROS start-up and on
    # sim time, so two share this 2-core machine well; ROTORS_TEST_WORKERS changes the number
    quick) set -- test rotors_gazebo_compat/rotors_evaluation/test -m "not long and not ros2" -n "${ROTORS_TEST_WORKERS:-2}" --dist loadgroup ;;
    long) set -- test -m "long and not ros2" ;;
    all) set -- test rotors_gazebo_compat/rotors_evaluation/test -m "not ros2" ;;
    # ROS 2 (make test-ros2; make setup installs the ROS 2 venv): the tests marked ros2
    ros2) set -- test -m ros2 ;;
    *) echo "ROTORS_TEST_TIER=${ROTORS_TEST_TIER} unknown (quick, long, all or ros2)" >&2; exit 2 ;;
  esac
fi
# the 25 slowest tests are listed at the end: what to move between the tiers (make test under 25 min)
exec python -m pytest -q -p no:cacheprovider --durations=25 "$@"
