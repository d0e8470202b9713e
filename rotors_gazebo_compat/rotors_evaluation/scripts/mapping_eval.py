#!/usr/bin/env python3
"""Mapping evaluation: a map built in flight against the world's octomap. Runs as
`rosrun rotors_evaluation mapping_eval.py -m built.bt -t truth.bt --save_plots True` (or
`--from_service CX CY CZ LX LY LZ` with the simulator running)."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))  # plain `python3 scripts/...` use

from rotors_evaluation.mapping import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
