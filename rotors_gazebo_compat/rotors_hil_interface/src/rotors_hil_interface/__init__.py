"""RotorS' HIL interface without mavros: hil_messages (ROS-free conversions) and the node."""
