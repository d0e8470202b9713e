"""RotorS' rosbag_tools.helpers: the command line of the evaluation scripts (initialize), the
evaluation period of each waypoint, settling time, RMS errors, collisions and the score table,
with RotorS' names, arguments, return values and printed lines."""

from __future__ import annotations

import sys

from rosbag_tools import analyze_bag
from rotors_evaluation import options


def get_score(evaluated_variable, max_variable, scores):
    """scores[0] above max_variable, [1] above half of it, [2] above a tenth, else [3]."""
    if evaluated_variable > max_variable:
        return scores[0]
    if evaluated_variable > 0.5 * max_variable:
        return scores[1]
    if evaluated_variable > 0.1 * max_variable:
        return scores[2]
    return scores[3]


def initialize(argv=None):
    """Reads the command line (RotorS' options: -b bag, -n mav_name, -p/-t/-m/-w/-W topics, -s, -d,
    --begin_time, -e, --rms_calc_time, --settling_radius, --min_settled_time, -D) and returns
    [AnalyzeBag with the messages extracted, plot, begin_time, end_time, rms_calc_time,
    settling_radius, min_settled_time, first_waypoint_evaluation_delay]."""
    o = options.parse("Evaluate a RotorS bag (rosbag_tools.helpers.initialize)", sys.argv[1:] if argv is None else argv)
    prefix = o.mav_name

    def topics(option):
        return [prefix + t for t in analyze_bag.create_topic_list(option)]

    ab = analyze_bag.AnalyzeBag(bag_path_name=o.bagfiles[0], save_plots=o.save_plots, prefix=o.prefix or None)
    for topic in topics(o.pose_topic):
        ab.add_pose_topic(topic)
    for topic in topics(o.twist_topic):
        ab.add_twist_topic(topic)
    for topic in topics(o.motor_velocity_topic):
        ab.add_motor_velocity_topic(topic)
    for topic in topics(o.waypoint_topic):
        ab.add_waypoint_topic(topic)
    for topic in topics(o.wrench_topic):
        ab.add_wrench_topic(topic)
    if ab.topics:
        ab.extract_messages()
    plot = bool(o.plot or o.save_plots)
    return [ab, plot, o.begin_time, o.end_time, o.rms_calc_time, o.settling_radius, o.min_settled_time, o.delay_first_evaluation]


def get_evaluation_period(waypoints, index, bag_time_start, bag_time_end, total_end_time):
    """[begin, end] [s from the bag's start] of waypoint `index`: from its publication to the next
    one's, the last to min(total_end_time, bag_time_end)."""
    begin_time = waypoints.bag_time[index].to_sec() - bag_time_start
    if index + 1 < len(waypoints.x):
        end_time = waypoints.bag_time[index + 1].to_sec() - bag_time_start
    else:
        end_time = min(total_end_time, bag_time_end)
    if bag_time_end < end_time:
        print(f"[Waypoint {index}]: Stopping evaluation early, as the bag file ends.")
    return [begin_time, end_time]


def get_settling_time(positions, set_point, radius, min_time, index, print_output=True):
    t = analyze_bag.settling_time(set_point, positions, radius, min_time)
    if print_output:
        print(f"[Waypoint {index}]: Settling time: {t:.3f} s" if t is not None else f"[Waypoint {index}]: System didn't settle.")
    return t


def get_rms_position_error(positions, position_set_point, index, print_output=True):
    rms = analyze_bag.xyz_rms_error(position_set_point, positions)
    if print_output:
        print(f"[Waypoint {index}]: Position RMS error: {rms:.3f} m")
    return rms


def get_rms_angular_velocity_error(angular_velocities, angular_velocity_set_point, index, print_output=True):
    rms = analyze_bag.xyz_rms_error(angular_velocity_set_point, angular_velocities)
    if print_output:
        print(f"[Waypoint {index}]: Angular velocity RMS error: {rms:.3f} rad/s")
    return rms


def _absolute(settling_time, start_time):
    return None if settling_time is None else settling_time + start_time


def plot_positions(analyze_bag, start_time, end_time, settling_time, settling_radius, set_point_position, x_range, plot_suffix):
    settled = _absolute(settling_time, start_time)
    analyze_bag.plot_positions(start_time=start_time, end_time=end_time, settling_time=settled, x_range=x_range, plot_suffix=plot_suffix)
    analyze_bag.plot_position_error(
        set_point=set_point_position,
        settling_radius=settling_radius,
        start_time=start_time,
        end_time=end_time,
        settling_time=settled,
        x_range=x_range,
        y_range=[0, 1],
        plot_suffix=plot_suffix,
    )


def plot_angular_velocities(analyze_bag, start_time, end_time, settling_time, x_range, plot_suffix):
    analyze_bag.plot_angular_velocities(
        start_time=start_time,
        end_time=end_time,
        settling_time=_absolute(settling_time, start_time),
        x_range=x_range,
        plot_suffix=plot_suffix,
        y_range=[-1.5, 1.5],
    )


def calculate_average(list_values):
    return sum(list_values) / len(list_values) if len(list_values) else None


def no_collisions_occured(analyze_bag, start_time, end_time):
    """Prints each collision (at most one a second) and returns whether there was none."""
    collisions = analyze_bag.get_collisions(start_time, end_time)
    print("\n")
    if not collisions:
        print("No collisions occurred - good job!")
        return True
    t_last = -1.0
    for t in collisions:
        if t - t_last >= 1:
            print(f"Collision at time {t:.3f}!")
            t_last = t
    print("One or more collisions occurred - no points are awarded!")
    return False


def print_scoring(average_value, max_value, value_type, unit, scores):
    if average_value is None:
        print(f"No {value_type} evaluated, hence no scoring is provided.")
        return
    print(f"Average {value_type}: {average_value:.3f} {unit}")
    print(f"Score for {value_type}: {get_score(average_value, max_value, scores):.2f}")
