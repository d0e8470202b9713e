"""Evaluation of RotorS flights from bags (Python 3, rosbags; works with or without ROS)."""
