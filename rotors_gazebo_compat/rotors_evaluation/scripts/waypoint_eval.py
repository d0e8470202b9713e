#!/usr/bin/env python3
"""Waypoint evaluation of a RotorS flight bag (Python 3, rosbags). Runs as
`rosrun rotors_evaluation waypoints_eval.py -b <bag> --save_plots True --mav_name firefly` or as a plain
script with only the PyPI dependencies."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))  # plain `python3 scripts/...` use

from rotors_evaluation.evaluations import run  # noqa: E402

if __name__ == "__main__":
    sys.exit(run("waypoints", __doc__))
