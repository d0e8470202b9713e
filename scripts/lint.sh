#!/usr/bin/env bash
# Linters over the project's own code, with the checked-in configs: ruff (ruff.toml) for Python,
# clang-format (.clang-format) for C++. Prints every finding and fails when there is one.
# `scripts/lint.sh --fix` rewrites the files instead.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
ruff="$root/build/venv/bin/ruff"
mapfile -t py < <({ git ls-files '*.py'; git ls-files | grep -v '\.py$' | xargs grep -l '^#!/usr/bin/env python' 2>/dev/null || true; } | sort -u)
mapfile -t cpp < <(git ls-files '*.cpp' '*.h' '*.hpp' '*.cc')
status=0
if [ "${1:-}" = --fix ]; then
  "$ruff" check --fix "${py[@]}" || status=1
  clang-format -i "${cpp[@]}"
  exit $status
fi
echo "[lint] ruff: ${#py[@]} Python files"
"$ruff" check --output-format concise "${py[@]}" || status=1
echo "[lint] clang-format: ${#cpp[@]} C++ files"
clang-format --dry-run --Werror "${cpp[@]}" || status=1
[ $status -eq 0 ] && echo "[lint] clean"
exit $status
