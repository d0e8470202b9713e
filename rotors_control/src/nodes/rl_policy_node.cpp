// rl_policy_node [--in-simulator]: see hover_policy_ros.h.
#include "controller_main.h"
#include "hover_policy_ros.h"

int main(int argc, char** argv) {
  return rotors_control::RunControllerNode<rotors_control::HoverPolicyRos>(argc, argv, "rl_policy_node");
}
