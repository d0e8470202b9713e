#!/usr/bin/env bash
# make test-sanitize: the C++ gtests and the Python-module tests under AddressSanitizer +
# UndefinedBehaviorSanitizer, then the batch / StepAll tests and a camera world stepped from many
# threads under ThreadSanitizer. Each sanitizer builds its own workspace (build/sanitize/<name>,
# RelWithDebInfo) over the source links of build/ws; any report fails the run (halt_on_error).
# CPython is not instrumented: the sanitizer runtime is preloaded, and leak checking is off for it
# (the interpreter keeps its objects at exit); the gtests run with leak checking on.
# scripts/test_sanitize.sh [asan|tsan|all]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
export PATH="$root/build/venv/bin:$PATH"
[ -d "$root/build/ws/src" ] || { echo "[sanitize] run make build first (build/ws/src holds the package links)" >&2; exit 1; }
jobs="-j$(nproc)"

build_sanitized() {  # name flags targets...: configure, then build only what the sanitized runs load
  local ws="$root/build/sanitize/$1" flags="$2"
  shift 2
  mkdir -p "$ws"
  ln -sfn "$root/build/ws/src" "$ws/src"
  local args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DCATKIN_ENABLE_TESTING=ON
              -DPYTHON_EXECUTABLE="$root/build/venv/bin/python3"
              "-DCMAKE_C_FLAGS=$flags" "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_EXE_LINKER_FLAGS=$flags"
              "-DCMAKE_SHARED_LINKER_FLAGS=$flags" "-DCMAKE_MODULE_LINKER_FLAGS=$flags")
  echo "[sanitize] building $ws: $* and every plugin (log: $ws/build.log)"
  # `catkin_make ... help` configures without building; then the targets, and every plugin library
  (cd "$ws" && catkin_make "${args[@]}" help > /dev/null &&
    make -C build "$jobs" "$@" && make -C build/rotors_gazebo_plugins "$jobs") > "$ws/build.log" 2>&1 || {
    tail -n 40 "$ws/build.log" >&2
    echo "[sanitize] the $ws build failed; the whole log is $ws/build.log" >&2
    exit 1
  }
}

run_in() {  # name preload pytest-args...
  local ws="$root/build/sanitize/$1" preload="$2"
  shift 2
  (
    set +u
    # shellcheck disable=SC1091
    source "$ws/devel/setup.bash"
    set -u
    export ROTORS_WS="$ws" ROTORS_SIM_ROOT="$root" SETUPTOOLS_USE_DISTUTILS=stdlib
    unset DISPLAY
    cd "$root"
    LD_PRELOAD="$preload" python -m pytest -q -p no:cacheprovider "$@"
  )
}

gcc_lib() { gcc -print-file-name="$1"; }
which="${1:-all}"  # asan, tsan or all

if [ "$which" != tsan ]; then
build_sanitized asan "-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" tests _engine
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
echo "[sanitize] ASan + UBSan: the gtests"
ASAN_OPTIONS="detect_leaks=1:halt_on_error=1" run_in asan "" test/test_cpp_units.py
echo "[sanitize] ASan + UBSan: the Python module"
ASAN_OPTIONS="detect_leaks=0:halt_on_error=1" \
  run_in asan "$(gcc_lib libasan.so) $(gcc_lib libubsan.so)" test/test_python_module.py
fi

if [ "$which" != asan ]; then
build_sanitized tsan "-fsanitize=thread -fno-omit-frame-pointer" _engine
echo "[sanitize] TSan: batches, step_all, a camera world from many threads"
TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$root/scripts/tsan.supp" \
  run_in tsan "$(gcc_lib libtsan.so)" test/test_python_module.py test/test_optical_flow.py \
  -k "batch or step_all or twice or new_thread"
fi
echo "[sanitize] clean"
