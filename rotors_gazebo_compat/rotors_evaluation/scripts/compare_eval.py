#!/usr/bin/env python3
"""Tabulates hovering metrics of several bags side by side:
compare_eval.py -b a.bag b.bag --mav_name firefly"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))  # plain `python3 scripts/...` use

from rotors_evaluation.evaluations import compare  # noqa: E402

if __name__ == "__main__":
    sys.exit(compare())
