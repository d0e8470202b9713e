#!/usr/bin/env bash
# make bench: engine and closed-loop figures on this machine (see README, Performance).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
set +u
# shellcheck disable=SC1091
source "$root/scripts/env.bash"
set -u
exec python3 "$root/scripts/bench.py"
