// lee_position_controller_node [--in-simulator]: see lee_position_controller_ros.h.
#include "controller_main.h"
#include "lee_position_controller_ros.h"

int main(int argc, char** argv) {
  return rotors_control::RunControllerNode<rotors_control::LeePositionControllerRos>(argc, argv,
                                                                                     "lee_position_controller_node");
}
