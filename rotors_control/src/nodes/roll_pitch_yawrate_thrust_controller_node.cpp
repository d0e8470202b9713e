// roll_pitch_yawrate_thrust_controller_node [--in-simulator]: see attitude_level_controller_ros.h.
#include "attitude_level_controller_ros.h"
#include "controller_main.h"

int main(int argc, char** argv) {
  return rotors_control::RunControllerNode<rotors_control::AttitudeLevelControllerRos>(
      argc, argv, "roll_pitch_yawrate_thrust_controller_node");
}
