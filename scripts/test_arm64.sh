#!/usr/bin/env bash
# make test-arm64: cross-builds the ROS-free libraries (rotors_plugins' models and autopilot
# protocols, rotors_control's controllers, the batch's kernels) and their gtests for arm64 with
# Debian's cross toolchain, and runs them under qemu-user (cmake/arm64/CMakeLists.txt). Installs
# g++-aarch64-linux-gnu and qemu-user when missing. The build is in build/arm64.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
start=$(date +%s)
missing=()
command -v aarch64-linux-gnu-g++ > /dev/null || missing+=(g++-aarch64-linux-gnu)
command -v qemu-aarch64 > /dev/null || missing+=(qemu-user)
if [ ${#missing[@]} -gt 0 ]; then
  echo "[test-arm64] installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}" > /dev/null
fi
python="$root/build/venv/bin/python3"
[ -x "$python" ] || python=python3
cmake -S "$root/cmake/arm64" -B "$root/build/arm64" -DCMAKE_TOOLCHAIN_FILE="$root/cmake/aarch64-linux-gnu.cmake" \
  -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE="$python" ${ROTORS_WERROR:+-DROTORS_WERROR=$ROTORS_WERROR} > /dev/null
cmake --build "$root/build/arm64" -j"$(nproc)"
file "$root/build/arm64/test_flight_kernel" | sed 's/, BuildID.*//'
(cd "$root/build/arm64" && ctest --output-on-failure -V | grep -E "^[0-9]+: (\[  PASSED|\[  FAILED|kernels of)|tests passed|Test +#" )
echo "[test-arm64] built and run in $(( $(date +%s) - start )) s"
