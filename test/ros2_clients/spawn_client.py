"""An rclpy client of the ROS 2 front end's spawning services (test_ros2_graph.py): it spawns a second
firefly from the URDF text in `urdf_path` with /spawn_entity at (2, 0, 0.1), receives its ground-truth
odometry (a topic that did not exist before), deletes it with /delete_entity, deletes it again and
spawns broken text (both refused with a message). Prints RESULT=<json>.
    python spawn_client.py <urdf_path> <budget_s>"""

import sys

import rclpy
from budget import Budget, report
from gazebo_msgs.srv import DeleteEntity, SpawnEntity
from nav_msgs.msg import Odometry

TOPIC = "/second/ground_truth/odometry"


def main() -> None:
    xml = open(sys.argv[1]).read()
    rclpy.init()
    node = rclpy.create_node("spawn_client")

    budget = Budget(node, float(sys.argv[2]), "spawn_client")

    def call(client, request):
        budget.until(client.service_is_ready, f"{client.srv_name} available")
        future = client.call_async(request)
        budget.until(future.done, f"{client.srv_name} answered")
        return future.result()

    spawn, delete = node.create_client(SpawnEntity, "/spawn_entity"), node.create_client(DeleteEntity, "/delete_entity")
    result: dict = {"before": TOPIC in dict(node.get_topic_names_and_types())}
    request = SpawnEntity.Request(name="second", xml=xml, robot_namespace="second")
    request.initial_pose.position.x, request.initial_pose.position.z, request.initial_pose.orientation.w = 2.0, 0.1, 1.0
    answer = call(spawn, request)
    result["spawn"] = [answer.success, answer.status_message]
    odometry = []
    node.create_subscription(Odometry, TOPIC, lambda m: odometry.append([m.header.frame_id, m.child_frame_id, m.pose.pose.position.x]), 100)
    budget.until(lambda: len(odometry) >= 5, f"5 messages on {TOPIC}")
    result["types"] = dict(node.get_topic_names_and_types()).get(TOPIC)
    result["odometry"] = odometry[-1]
    answer = call(delete, DeleteEntity.Request(name="second"))
    result["delete"] = [answer.success, answer.status_message]
    answer = call(delete, DeleteEntity.Request(name="second"))
    result["delete_again"] = [answer.success, answer.status_message]
    answer = call(spawn, SpawnEntity.Request(name="third", xml="not a robot"))
    result["spawn_broken"] = [answer.success, answer.status_message]
    report(node, result)


if __name__ == "__main__":
    main()
