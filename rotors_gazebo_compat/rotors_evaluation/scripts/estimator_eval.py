#!/usr/bin/env python3
"""Estimator evaluation of a flight bag (ours): the estimate (msf_core/odometry, cov_core,
state_out) against the simulator's ground truth: estimator RMS, bias estimates, NEES.
`rosrun rotors_evaluation estimator_eval.py -b <bag> --mav_name firefly --save_plots True`"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))  # plain `python3 scripts/...` use

from rotors_evaluation.estimator import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main())
