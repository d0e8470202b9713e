"""RotorS evaluation's rosbag_tools module (RotorS' rotors_evaluation/src/rosbag_tools): `analyze_bag` (AnalyzeBag and
the time-series classes) and `helpers` (the evaluation scripts' shared functions), with RotorS'
names, fields and behaviour, so user scripts written against RotorS' module run unchanged. Bags
are read with rosbags (no rosbag, tf or scipy needed)."""
