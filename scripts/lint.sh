#!/usr/bin/env bash
# Linters over the project's own code, with the checked-in configs: ruff (ruff.toml: its rules and
# `ruff format`) for Python, clang-format (.clang-format) for C++, clang-tidy (.clang-tidy) on the
# ROS-free C++ libraries (it reads the workspace's compile_commands.json: run `make build` first).
# Prints every finding and fails when there is one.
#   scripts/lint.sh                    every check (make lint)
#   scripts/lint.sh --fix              rewrites what can be rewritten (ruff --fix, ruff format, clang-format)
#   scripts/lint.sh --clang-tidy F...  clang-tidy on the given files (the pre-commit hook)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
ruff="$root/build/venv/bin/ruff"
compile_db="$root/build/ws/build"
# the ROS-free libraries clang-tidy checks (the engine's physics, the models, the autopilot codecs,
# the controller library, the batched flight engine)
tidy_dirs=(rotors_core_cpp/src/physics rotors_plugins/src/models rotors_plugins/src/autopilot
  rotors_control/src/library rotors_flight_batch/src)

clang_tidy() {
  if [ ! -f "$compile_db/compile_commands.json" ]; then
    echo "clang-tidy needs $compile_db/compile_commands.json: run make build first" >&2
    return 1
  fi
  # the workspace's commands without GCC's precompiled headers (clang cannot read a .gch; every
  # file includes what it uses, the headers only make GCC faster) and without GCC's warning
  # switches: clang does not know -Wno-maybe-uninitialized, and under CI's -Werror (ROTORS_WERROR)
  # an unknown option is an error; .clang-tidy decides what is an error here. Nor does it know GCC's
  # tuning switches -m(no-)avx256-split-unaligned-load/store (the AVX2 kernel's code generation).
  local db="$root/build/lint"
  mkdir -p "$db"
  python3 - "$compile_db/compile_commands.json" "$db/compile_commands.json" <<'PY'
import json, re, sys
entries = json.load(open(sys.argv[1]))
for e in entries:
    e["command"] = re.sub(
        r"(?<!\S)(-include \S*cmake_pch\.hxx|-Winvalid-pch|-Werror|-Wno-maybe-uninitialized"
        r"|-m(no-)?avx256-split-unaligned-(load|store))(?!\S)",
        "", e["command"])
json.dump(entries, open(sys.argv[2], "w"))
PY
  # one process per core; clang-tidy prints findings to stdout, its progress notes to stderr
  printf '%s\n' "$@" | xargs -r -P "$(nproc)" -n 4 clang-tidy -p "$db" --quiet 2>/dev/null
}

if [ "${1:-}" = --clang-tidy ]; then
  shift
  clang_tidy "$@"
  exit $?
fi

mapfile -t py < <({ git ls-files '*.py'; git ls-files | grep -v '\.py$' | xargs grep -l '^#!/usr/bin/env python' 2>/dev/null || true; } | sort -u)
mapfile -t cpp < <(git ls-files '*.cpp' '*.h' '*.hpp' '*.cc')
mapfile -t tidy < <(git ls-files "${tidy_dirs[@]/%//*.cpp}")
status=0
if [ "${1:-}" = --fix ]; then
  "$ruff" check --fix "${py[@]}" || status=1
  "$ruff" format "${py[@]}"
  clang-format -i "${cpp[@]}"
  exit $status
fi
echo "[lint] ruff check: ${#py[@]} Python files"
"$ruff" check --output-format concise "${py[@]}" || status=1
echo "[lint] ruff format --check"
"$ruff" format --check "${py[@]}" || status=1
echo "[lint] clang-format: ${#cpp[@]} C++ files"
clang-format --dry-run --Werror "${cpp[@]}" || status=1
echo "[lint] clang-tidy: ${#tidy[@]} files of the ROS-free libraries"
clang_tidy "${tidy[@]}" || status=1
[ $status -eq 0 ] && echo "[lint] clean"
exit $status
