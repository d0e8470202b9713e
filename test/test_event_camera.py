"""End to end: the event camera (dvs_camera_macro, librotors_gazebo_dvs_plugin.so) beside the
VI-sensor on the hovering firefly (mav_hovering_example_with_vi_sensor.launch enable_dvs:=true):
dvs_msgs/EventArray arrives on <mav>/dvs/events with events of both polarities inside the
346 x 260 array, in time order, none after its array's stamp, and frames on image_raw beside."""

import os

import clients.event_camera
from support import RosGraph, launch, stop_launch


def test_event_camera_fires_while_the_firefly_climbs(ros: RosGraph):
    proc = launch(
        ros, "rotors_gazebo", "mav_hovering_example_with_vi_sensor.launch", "enable_dvs:=true", "gui:=false",
        "lockstep:=true", "real_time_factor:=0",
    )  # fmt: skip
    try:
        # ROTORS_FIGURE_DIR: docs/sensor_realism.md's figure
        figure = os.path.join(os.environ["ROTORS_FIGURE_DIR"], "dvs.png") if "ROTORS_FIGURE_DIR" in os.environ else ""
        r = ros.run_client(clients.event_camera.events_while_flying, until_s=7.0, figure=figure, timeout=400)
    finally:
        stop_launch(proc)
    print(r)
    assert r["arrays"] > 50 and (r["width"], r["height"]) == (346, 260)
    assert r["events"] > 1000 and 0 < r["positive"] < r["events"], "both polarities while the view moves"
    assert r["max_x"] < 346 and r["max_y"] < 260
    assert r["in_order"] and r["stamped_before_their_array"]
    assert r["image"] == [346, 260, "mono8"] and r["frame"] == "firefly/camera_dvs_optical_link"
