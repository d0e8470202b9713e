"""A user's evaluation script written against RotorS' rosbag_tools module only (helpers.initialize,
AnalyzeBag's series, slice, the RMS, settling and collision helpers, the scoring and the plots), as
scripts based on RotorS' hovering_eval.py are: every waypoint's settling time and RMS errors."""

from rosbag_tools import analyze_bag, helpers


def main():
    [ab, plot, begin_time, total_end_time, rms_calc_time, settling_radius, min_settled_time, delay] = helpers.initialize()
    waypoints = ab.waypoint[0]
    start, end = ab.bag_time_start.to_sec(), ab.bag_time_end.to_sec()
    position_errors = []
    for index in range(len(waypoints.x)):
        begin, finish = helpers.get_evaluation_period(waypoints, index, start, end, total_end_time)
        print(
            f"[Waypoint {index}]: [{waypoints.x[index]:.3f}, {waypoints.y[index]:.3f}, {waypoints.z[index]:.3f}] "
            f"from {begin:.3f} s to {finish:.3f} s"
        )
        set_point = analyze_bag.create_set_point(waypoints.x[index], waypoints.y[index], waypoints.z[index])
        positions = ab.pos[0].slice(begin, finish)
        settled = helpers.get_settling_time(positions, set_point, settling_radius, min_settled_time, index)
        rms_begin = begin + (settled if settled is not None else delay)
        rms_end = min(rms_begin + rms_calc_time, finish)
        position_errors.append(helpers.get_rms_position_error(ab.pos[0].slice(rms_begin, rms_end), set_point, index))
        helpers.get_rms_angular_velocity_error(ab.pqr[0].slice(rms_begin, rms_end), analyze_bag.create_set_point(0, 0, 0), index)
        if plot:
            helpers.plot_positions(ab, begin, rms_end, settled, settling_radius, set_point, None, str(index))
            helpers.plot_angular_velocities(ab, begin, rms_end, settled, None, str(index))
    if helpers.no_collisions_occured(ab, waypoints.bag_time[0].to_sec() + delay, end):
        helpers.print_scoring(helpers.calculate_average(position_errors), 0.2, "position RMS error", "m", [0.0, 1.5, 3.5, 5.0])


if __name__ == "__main__":
    main()
