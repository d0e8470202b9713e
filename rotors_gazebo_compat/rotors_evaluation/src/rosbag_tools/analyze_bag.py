"""RotorS' analyze_bag API: time series of a bag's poses, twists, IMU, motor speeds, waypoints and
wrenches (AnalyzeBag), their RMS error and settling time, and their plots.

Same names and fields as RotorS. Differences, all fixes: IMU accelerations and mav_msgs/Actuators
motor speeds are read (RotorS appended to numpy arrays with list methods, and read only the old
MotorSpeed message); a series that settles at its first sample (time 0.0) counts as settled;
`resample` interpolates linearly (RotorS used an FFT resampling that rings at the ends)."""

from __future__ import annotations

import copy
import math
import os

import numpy

from rotors_evaluation.bag_data import FlightBag


class BagTime(float):
    """A bag time [s]: a float that also answers `to_sec()`, as the rospy.Time RotorS' scripts use."""

    def to_sec(self) -> float:
        return float(self)


def _euler_from_quaternion(x, y, z, w):
    """(roll, pitch, yaw) [rad] of R = Rz(yaw) Ry(pitch) Rx(roll) (tf's 'sxyz')."""
    roll = math.atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2.0 * (w * y - z * x))))
    yaw = math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))
    return roll, pitch, yaw


class BaseWithTime:
    """Message times (header stamps) [s] and bag times (BagTime) of a series."""

    def __init__(self):
        self.time = numpy.array([])
        self.bag_time = numpy.array([], dtype=object)

    def append_times(self, msg_time, bag_time):
        self.time = numpy.append(self.time, msg_time)
        self.bag_time = numpy.append(self.bag_time, numpy.array([bag_time], dtype=object))

    def slice(self, start_time, end_time):
        """A copy holding the samples with start_time < time <= end_time (RotorS' index rule)."""
        start_index, end_index = self.get_next_index(start_time), self.get_next_index(end_time)
        copied = copy.deepcopy(self)
        for key, value in self.__dict__.items():
            if isinstance(value, numpy.ndarray):
                setattr(copied, key, value[start_index:end_index])
        return copied

    def get_next_index(self, time):
        """The index of the first sample after `time` (len when there is none)."""
        return int(numpy.searchsorted(self.time, time, side="right"))


class ArrayWithTime(BaseWithTime):
    """A vector per sample (motor speeds), rows of `data`."""

    def __init__(self):
        self.data = numpy.array([])
        BaseWithTime.__init__(self)

    def append_array(self, array):
        row = numpy.array([numpy.asarray(array, dtype=float)])
        self.data = row if self.data.size == 0 else numpy.append(self.data, row, axis=0)


class QuatWithTime(BaseWithTime):
    def __init__(self):
        self.w = numpy.array([])
        self.x = numpy.array([])
        self.y = numpy.array([])
        self.z = numpy.array([])
        BaseWithTime.__init__(self)

    def append_quaternion(self, quaternion_msg):
        for axis in "wxyz":
            setattr(self, axis, numpy.append(getattr(self, axis), getattr(quaternion_msg, axis)))


class XYZWithTime(BaseWithTime):
    def __init__(self):
        self.x = numpy.array([])
        self.y = numpy.array([])
        self.z = numpy.array([])
        BaseWithTime.__init__(self)

    def append_point(self, point_msg):
        for axis in "xyz":
            setattr(self, axis, numpy.append(getattr(self, axis), getattr(point_msg, axis)))

    def resample(self, sampling_times):
        """The series at sampling_times (linear interpolation)."""
        sampling_times = numpy.asarray(sampling_times, dtype=float)
        for axis in "xyz":
            setattr(self, axis, numpy.interp(sampling_times, self.time, getattr(self, axis)))
        self.time = sampling_times


class WrenchWithTime(BaseWithTime):
    """Contact wrenches (the bag plugin's wrench topic): one sample per collision."""

    def __init__(self):
        for name in ("force_x", "force_y", "force_z", "torque_x", "torque_y", "torque_z"):
            setattr(self, name, numpy.array([]))
        BaseWithTime.__init__(self)

    def append_wrench(self, wrench_msg):
        w = wrench_msg.wrench
        for kind, vector in (("force", w.force), ("torque", w.torque)):
            for axis in "xyz":
                name = f"{kind}_{axis}"
                setattr(self, name, numpy.append(getattr(self, name), getattr(vector, axis)))


class _Point:
    def __init__(self, x, y, z):
        self.x, self.y, self.z = x, y, z


class WaypointWithTime(XYZWithTime):
    """The set points of a trajectory topic (its first point), each kept once while it repeats."""

    def __init__(self):
        self.yaw = numpy.array([])
        XYZWithTime.__init__(self)
        self.empty = True

    def append_waypoint(self, waypoint_msg, msg_time, bag_time):
        transform = waypoint_msg.points[0].transforms[0]
        p, q = transform.translation, transform.rotation
        yaw = _euler_from_quaternion(q.x, q.y, q.z, q.w)[2]
        if len(self.x) and (self.x[-1], self.y[-1], self.z[-1], self.yaw[-1]) == (p.x, p.y, p.z, yaw):
            return
        self.append_point(_Point(p.x, p.y, p.z))
        self.yaw = numpy.append(self.yaw, yaw)
        self.append_times(msg_time, bag_time)
        self.empty = False


class RPYWithTime(BaseWithTime):
    """Roll, pitch and yaw [deg]."""

    def __init__(self):
        self.roll = numpy.array([])
        self.pitch = numpy.array([])
        self.yaw = numpy.array([])
        BaseWithTime.__init__(self)

    def append_quaternion(self, quaternion_msg):
        q = quaternion_msg
        for name, angle in zip(("roll", "pitch", "yaw"), _euler_from_quaternion(q.x, q.y, q.z, q.w)):
            setattr(self, name, numpy.append(getattr(self, name), math.degrees(angle)))


_IDENTITY = _Point(0.0, 0.0, 0.0)
_IDENTITY.w = 1.0


class AnalyzeBag:
    """Add the topics to read (add_*_topic), call extract_messages(), then use the series: pos, quat,
    rpy (one per pose topic), pqr (per twist topic), acc (per IMU topic), motor_vel, waypoint, wrench."""

    def __init__(self, bag_path_name, save_plots, prefix=None):
        self.bag = FlightBag(bag_path_name)  # BagError naming a missing, empty or unreadable bag
        self.topics = []
        self.pose_topics, self.twist_topics, self.imu_topics = [], [], []
        self.motor_velocity_topics, self.waypoint_topics, self.wrench_topics = [], [], []
        self.pos, self.quat, self.rpy, self.pqr, self.motor_vel = [], [], [], [], []
        self.acc, self.ang_vel, self.waypoint, self.wrench = [], [], [], []
        self.save_plots = save_plots
        self.bag_time_start = None
        self.bag_time_end = None
        self.prefix = prefix

    def _add(self, topic, topic_list, *series):
        topic_list.append(topic)
        self.topics.append(topic)
        for series_list, cls in series:
            series_list.append(cls())

    def add_pose_topic(self, topic):
        self._add(topic, self.pose_topics, (self.pos, XYZWithTime), (self.quat, QuatWithTime), (self.rpy, RPYWithTime))

    def add_twist_topic(self, topic):
        self._add(topic, self.twist_topics, (self.pqr, XYZWithTime))

    def add_imu_topic(self, topic):
        self._add(topic, self.imu_topics, (self.acc, XYZWithTime), (self.ang_vel, XYZWithTime))

    def add_motor_velocity_topic(self, topic):
        self._add(topic, self.motor_velocity_topics, (self.motor_vel, ArrayWithTime))

    def add_waypoint_topic(self, topic):
        self._add(topic, self.waypoint_topics, (self.waypoint, WaypointWithTime))

    def add_wrench_topic(self, topic):
        self._add(topic, self.wrench_topics, (self.wrench, WrenchWithTime))

    def extract_messages(self):
        """Reads every added topic that the bag holds (a topic it lacks stays an empty series)."""
        extractors = (
            (self.pose_topics, self._pose),
            (self.twist_topics, self._twist),
            (self.imu_topics, self._imu),
            (self.motor_velocity_topics, self._motor_velocity),
            (self.waypoint_topics, self._waypoint),
            (self.wrench_topics, self._wrench),
        )
        for topics, extract in extractors:
            for index, topic in enumerate(topics):
                for msg, msgtype, t_ns in self.bag.messages(topic):
                    bag_time = BagTime(t_ns * 1e-9)
                    self.bag_time_start = bag_time if self.bag_time_start is None else min(self.bag_time_start, bag_time)
                    self.bag_time_end = bag_time if self.bag_time_end is None else max(self.bag_time_end, bag_time)
                    stamp = msg.header.stamp
                    extract(index, msg, msgtype, stamp.sec + stamp.nanosec * 1e-9, bag_time)

    def _pose(self, index, msg, msgtype, t, bag_time):
        if msgtype.endswith("PoseStamped"):
            position, orientation = msg.pose.position, msg.pose.orientation
        elif msgtype.endswith("TransformStamped"):
            position, orientation = msg.transform.translation, msg.transform.rotation
        elif msgtype.endswith("PointStamped"):
            position, orientation = msg.point, _IDENTITY
        elif msgtype.endswith("Odometry"):
            position, orientation = msg.pose.pose.position, msg.pose.pose.orientation
        else:
            print(f"Got unknown type: {msgtype} on pose topic {self.pose_topics[index]}")
            return
        for series, append in ((self.pos, "append_point"), (self.quat, "append_quaternion"), (self.rpy, "append_quaternion")):
            getattr(series[index], append)(position if append == "append_point" else orientation)
            series[index].append_times(t, bag_time)

    def _twist(self, index, msg, msgtype, t, bag_time):
        angular = msg.twist.twist.angular if msgtype.endswith("Odometry") else msg.twist.angular
        self.pqr[index].append_point(angular)
        self.pqr[index].append_times(t, bag_time)

    def _imu(self, index, msg, msgtype, t, bag_time):
        self.acc[index].append_point(msg.linear_acceleration)
        self.acc[index].append_times(t, bag_time)
        self.ang_vel[index].append_point(msg.angular_velocity)
        self.ang_vel[index].append_times(t, bag_time)

    def _motor_velocity(self, index, msg, msgtype, t, bag_time):
        speeds = msg.angular_velocities if hasattr(msg, "angular_velocities") else msg.motor_speed
        self.motor_vel[index].append_array(speeds)
        self.motor_vel[index].append_times(t, bag_time)

    def _waypoint(self, index, msg, msgtype, t, bag_time):
        self.waypoint[index].append_waypoint(msg, t, bag_time)

    def _wrench(self, index, msg, msgtype, t, bag_time):
        self.wrench[index].append_wrench(msg)
        self.wrench[index].append_times(t, bag_time)

    # ---- plots (saved as <prefix>_<name>[_<suffix>].png in the working directory when save_plots) ----

    def _figure(self, title):
        from matplotlib import pyplot

        fig = pyplot.figure()
        fig.suptitle(title)
        return fig, fig.add_subplot(111)

    @staticmethod
    def _mark_times(ax, start_time, end_time, settling_time):
        for t, color, label in (
            (start_time, "c", "start evaluation"),
            (end_time, "m", "end evaluation"),
            (settling_time, "k", "settled, start RMS eval"),
        ):
            if t:
                ax.axvline(x=t, color=color, label=label)

    def _finish(self, fig, ax, name, plot_suffix, x_range=None, y_range=None, xlabel="time [s]", ylabel=""):
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        if x_range:
            ax.set_xlim(x_range)
        if y_range:
            ax.set_ylim(y_range)
        ax.legend(loc="best", fontsize="small")
        if self.save_plots:
            file_name = (self.prefix + "_" + name) if self.prefix else name
            if plot_suffix:
                file_name += "_" + str(plot_suffix)
            fig.savefig(file_name + ".png")
        return fig

    def plot_positions(self, start_time=None, end_time=None, settling_time=None, x_range=None, y_range=None, plot_suffix=None):
        fig, ax = self._figure("Position")
        for pos, topic in zip(self.pos, self.pose_topics):
            for axis, color in zip("xyz", "brg"):
                ax.plot(pos.time, getattr(pos, axis), color, label=f"{axis} {topic}")
        self._mark_times(ax, start_time, end_time, settling_time)
        return self._finish(fig, ax, "pos", plot_suffix, x_range, y_range, ylabel="position [m]")

    def plot_position_error(
        self,
        set_point,
        settling_radius=None,
        start_time=None,
        end_time=None,
        settling_time=None,
        x_range=None,
        y_range=None,
        plot_suffix=None,
    ):
        fig, ax = self._figure("Position error")
        for pos, topic in zip(self.pos, self.pose_topics):
            error = numpy.sqrt((pos.x - set_point.x[0]) ** 2 + (pos.y - set_point.y[0]) ** 2 + (pos.z - set_point.z[0]) ** 2)
            ax.plot(pos.time, error, "b", label=f"pos_error {topic}")
        if settling_radius:
            ax.axhline(y=settling_radius, color="r", label="settling radius")
        self._mark_times(ax, start_time, end_time, settling_time)
        return self._finish(fig, ax, "pos_error", plot_suffix, x_range, y_range, ylabel="position error [m]")

    def plot_angular_velocities(self, start_time=None, end_time=None, settling_time=None, x_range=None, y_range=None, plot_suffix=None):
        fig, ax = self._figure("Angular velocities")
        for pqr, topic in zip(self.pqr, self.twist_topics):
            for axis, color, name in zip("xyz", "brg", ("p", "q", "r")):
                ax.plot(pqr.time, getattr(pqr, axis), color, label=f"{name} {topic}")
        self._mark_times(ax, start_time, end_time, settling_time)
        return self._finish(fig, ax, "angular_velocity", plot_suffix, x_range, y_range, ylabel="angular velocity [rad/s]")

    def plot_3d_trajectories(self):
        from matplotlib import pyplot

        fig = pyplot.figure()
        ax = fig.add_subplot(111, projection="3d")
        for pos, topic in zip(self.pos, self.pose_topics):
            ax.plot(pos.x, pos.y, pos.z, label=topic)
        ax.legend(loc="best", fontsize="small")
        return fig

    def plot_rpys(self, start_time=None, end_time=None, settling_time=None, x_range=None, y_range=None, plot_suffix=None):
        fig, ax = self._figure("Attitude")
        for rpy, topic in zip(self.rpy, self.pose_topics):
            for name, color in zip(("roll", "pitch", "yaw"), "brg"):
                ax.plot(rpy.time, getattr(rpy, name), color, label=name + topic)
        self._mark_times(ax, start_time, end_time, settling_time)
        return self._finish(fig, ax, "rpy", plot_suffix, x_range, y_range, ylabel="angle [deg]")

    def plot_accelerations(self, plot_suffix=None):
        fig, ax = self._figure("Accelerations")
        for acc, topic in zip(self.acc, self.imu_topics):
            for axis, color in zip("xyz", "brg"):
                ax.plot(acc.time, getattr(acc, axis), color, label=axis + topic)
        return self._finish(fig, ax, "acc", plot_suffix, ylabel="acceleration [m/s^2]")

    def compare_positions(self, pose_indeces):
        """RotorS declares it and implements nothing; so it is here: it only checks its argument."""
        if len(pose_indeces) < 2:
            print("At least two pose_indeces need to be provided to make a comparison")

    def get_collisions(self, start_time=None, end_time=None):
        """The times [s] of the wrench samples (collisions) within [start_time, end_time]."""
        times = []
        for collision in self.wrench:
            if not len(collision.time):
                continue
            last = end_time if end_time is not None else collision.time.max()
            times += [t for t in collision.time if (start_time or 0) <= t <= last]
        return times


def xyz_rms_error(set_point, input_series):
    """RMS of the distance [m] between the points of input_series and set_point (XYZWithTime)."""
    if not len(input_series.x):
        return 0.0
    squared = (
        (input_series.x - _first(set_point.x)) ** 2
        + (input_series.y - _first(set_point.y)) ** 2
        + (input_series.z - _first(set_point.z)) ** 2
    )
    return float(numpy.sqrt(numpy.mean(squared)))


def _first(value):
    return float(numpy.asarray(value).ravel()[0])


def settling_time(set_point, input_series, bounding_radius, min_time):
    """The time from the series' start until it entered the sphere of bounding_radius around
    set_point and stayed inside for min_time; None when it never did."""
    entered = None
    for t, x, y, z in zip(input_series.time, input_series.x, input_series.y, input_series.z):
        inside = (
            math.sqrt((x - _first(set_point.x)) ** 2 + (y - _first(set_point.y)) ** 2 + (z - _first(set_point.z)) ** 2) <= bounding_radius
        )
        if not inside:
            entered = None
            continue
        if entered is None:
            entered = t
        if t - entered >= min_time:
            return entered - input_series.time[0]
    return None


def work(input_series, work_constant):
    """Sum over samples and rotors of |w|^3 * work_constant * dt (motor speeds in ArrayWithTime)."""
    total = 0.0
    for index in range(len(input_series.time) - 1):
        dt = input_series.time[index + 1] - input_series.time[index]
        total += float(numpy.sum(numpy.abs(input_series.data[index]) ** 3)) * work_constant * dt
    return total


def create_topic_list(topics_string):
    """'a,b' -> ['a', 'b']; '' or None -> []."""
    return topics_string.split(",") if topics_string else []


def create_set_point(x, y, z):
    set_point = XYZWithTime()
    set_point.append_point(_Point(x, y, z))
    return set_point


def _headless():
    if not os.environ.get("DISPLAY"):
        import matplotlib

        matplotlib.use("Agg")


_headless()
