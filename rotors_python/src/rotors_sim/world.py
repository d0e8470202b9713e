"""rotors_sim.World: one simulated world, its vehicles and sensors, stepped from Python.

The plugins are the ones the ROS simulator loads (same code); with no ROS master they publish
into the world's message taps, which `message()` reads as the ROS message classes.
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import xacro

from rotors_sim import _engine
from rotors_sim._engine import SimError
from rotors_sim.paths import package_path, world_file


def known_vehicles() -> list[str]:
    """Vehicles with a mechanics file <name>.xacro beside <name>_base.xacro (as rotors_xacro checks)."""
    urdf = package_path("rotors_description") / "urdf"
    return sorted(
        p.name[: -len("_base.xacro")] for p in urdf.glob("*_base.xacro") if (urdf / p.name.replace("_base.xacro", ".xacro")).exists()
    )


def run_xacro(path: str | Path, args: dict[str, Any]) -> str:
    """The URDF text of a xacro file with arguments (booleans written as xacro reads them)."""
    mappings = {k: (str(v).lower() if isinstance(v, bool) else str(v)) for k, v in args.items()}
    try:
        return xacro.process_file(str(path), mappings=mappings).toprettyxml(indent="  ")
    except Exception as e:  # xacro raises XacroException, ParseError, NameError, ...
        raise SimError(f"xacro {Path(path).name}: {e}") from None


@functools.cache
def message_class(datatype: str) -> type:
    """The Python class of a ROS message type, e.g. 'sensor_msgs/Imu'."""
    package, name = datatype.split("/")
    return getattr(importlib.import_module(f"{package}.msg"), name)


@dataclass
class Odometry:
    """nav_msgs/Odometry as the controllers take it: time, position_W, orientation (x, y, z, w),
    velocity_B and angular_velocity_B (body frame, as RotorS' odometry plugin publishes them)."""

    time_s: float
    position_W: np.ndarray
    orientation: np.ndarray
    velocity_B: np.ndarray
    angular_velocity_B: np.ndarray
    count: int


@dataclass
class Imu:
    """An IMU's reading as sensor_msgs/Imu carries it, in the IMU's frame: time, angular_velocity
    [rad/s] and linear_acceleration (the specific force) [m/s^2]."""

    time_s: float
    angular_velocity: np.ndarray
    linear_acceleration: np.ndarray
    count: int


class World:
    """A world from rotors_gazebo/worlds (by name), a .world file, or SDF text (`sdf=`)."""

    def __init__(self, name_or_path: str | Path = "basic", *, sdf: str | None = None, step_size: float | None = None, shadows: bool = True):
        """`step_size` [s] overrides the world file's max_step_size (e.g. 0.002 for 500 Hz physics);
        `shadows=False` draws no shadows whatever the world says (faster cameras)."""
        _engine.add_model_path(str(package_path("rotors_gazebo") / "models"))  # model://asphalt_plane, ...
        if sdf is not None:
            self._w = _engine.World.load_string(sdf, "<string>", shadows)
        else:
            self._w = _engine.World.load_file(str(world_file(str(name_or_path))), shadows)
        if step_size is not None:
            self._w.step_size = float(step_size)
        self._vehicles: dict[str, str] = {}  # namespace -> model name

    # --- vehicles ---
    def spawn(
        self,
        description: str | Path,
        name: str,
        xyz: Sequence[float] = (0.0, 0.0, 0.0),
        rpy: Sequence[float] = (0.0, 0.0, 0.0),
        **xacro_args: Any,
    ) -> str:
        """Spawns a model from URDF/SDF text, or from a .urdf/.sdf/.xacro/.gazebo file (run through
        xacro with `xacro_args`). Returns the model name."""
        text = str(description)
        if not text.lstrip().startswith("<"):
            path = Path(text)
            if not path.exists():
                raise SimError(f"model file '{path}' does not exist")
            text = path.read_text() if path.suffix in (".urdf", ".sdf") and not xacro_args else run_xacro(path, xacro_args)
        return self._w.spawn(text, name, list(map(float, xyz)), list(map(float, rpy)))

    def spawn_mav(
        self,
        mav_name: str = "firefly",
        namespace: str | None = None,
        xyz: Sequence[float] = (0.0, 0.0, 0.1),
        rpy: Sequence[float] = (0.0, 0.0, 0.0),
        random_seed: int = -1,
        model: str | Path | None = None,
        **xacro_args: Any,
    ) -> str:
        """A RotorS vehicle as spawn_mav.launch spawns it: `model` defaults to
        mav_generic_odometry_sensor.gazebo (the hovering example's), `random_seed` seeds every sensor
        noise (-1: from the clock). Further xacro arguments as keywords (enable_logging=False, ...)."""
        known = known_vehicles()
        if mav_name not in known:
            raise SimError(f"unknown vehicle mav_name '{mav_name}' (known: {' '.join(known)})")
        namespace = namespace or mav_name
        path = model or package_path("rotors_description") / "urdf" / "mav_generic_odometry_sensor.gazebo"
        args = dict(
            mav_name=mav_name,
            namespace=namespace,
            random_seed=random_seed,
            enable_logging=False,
            enable_ground_truth=True,
            log_file=mav_name,
            wait_to_record_bag=False,
            enable_mavlink_interface=False,
        )
        args.update(xacro_args)
        name = self.spawn(path, namespace, xyz, rpy, **args)
        self._vehicles[namespace] = name
        return name

    def remove(self, name: str) -> bool:
        return self._w.remove_model(name)

    # --- time ---
    def step(self, n: int = 1) -> None:
        """Advances n physics steps (the GIL released meanwhile)."""
        self._w.step(int(n))

    def reset(self) -> None:
        """Gazebo's reset_simulation: time 0, models at their spawn poses, every plugin reset (noise
        generators at their seeds again, an external wind forgotten): a flight after it repeats the
        first one bit for bit."""
        self._w.reset()

    def reset_world(self) -> None:
        """Gazebo's reset_world: as reset(), but the time runs on."""
        self._w.reset_world()

    @property
    def time(self) -> float:
        return self._w.time

    @property
    def step_size(self) -> float:
        return self._w.step_size

    @property
    def engine(self) -> _engine.World:
        return self._w

    # --- state ---
    def models(self) -> list[str]:
        return self._w.model_names()

    def link_state(self, model: str, link: str = "") -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(position_W, orientation (x, y, z, w), velocity_W, angular_velocity_W); the canonical link by default."""
        return self._w.link_state(model, link)

    def set_model_state(
        self,
        model: str,
        position: Sequence[float],
        orientation: Sequence[float] = (0, 0, 0, 1),
        velocity: Sequence[float] = (0, 0, 0),
        angular_velocity: Sequence[float] = (0, 0, 0),
    ) -> None:
        self._w.set_model_state(
            model, list(map(float, position)), list(map(float, orientation)), list(map(float, velocity)), list(map(float, angular_velocity))
        )

    def set_motor_speeds(self, namespace: str, speeds: Sequence[float]) -> None:
        """The motor command [rad/s], as command/motor_speed would give it (validated the same way)."""
        self._w.set_motor_speeds(namespace, [float(s) for s in np.asarray(speeds, dtype=float).ravel()])

    def set_actuators(self, namespace: str, normalized: Sequence[float]) -> None:
        """A fixed wing's command: surfaces and throttle by channel, as Actuators.normalized."""
        self._w.set_actuators(namespace, [float(x) for x in normalized])

    def rotor_speeds(self, namespace: str) -> np.ndarray:
        return np.asarray(self._w.rotor_speeds(namespace))

    def set_rc(self, namespace: str, channels_us: Sequence[int]) -> None:
        """RC channels [us] (AETR, AUX1.., at most 16, 800..2200) for the vehicle's autopilot interface."""
        self._w.set_rc(namespace, [int(c) for c in channels_us])

    def autopilot_answers(self, namespace: str) -> int:
        """How many times the vehicle's autopilot (PX4, ArduPilot, Betaflight) has sent its outputs."""
        return self._w.autopilot_answers(namespace)

    def contacts(self) -> list[dict]:
        return self._w.contacts()

    def in_contact(self, model: str) -> bool:
        """Whether the model touched anything (another model, the ground) in the last step."""
        return self._w.in_contact(model)

    # --- sensors ---
    def topics(self) -> list[tuple[str, str, int]]:
        """(topic, message type, messages so far) of everything the plugins publish."""
        return self._w.topics()

    def message(self, topic: str) -> tuple[Any, int] | None:
        """(the last message of `topic` as its ROS message class, messages so far), None before the first."""
        got = self._w.message(topic)
        if got is None:
            if topic not in {t for t, _, _ in self._w.topics()}:
                raise SimError(f"no plugin publishes '{topic}' (topics: {' '.join(t for t, _, _ in self._w.topics())})")
            return None
        datatype, count, data = got
        return message_class(datatype)().deserialize(data), count

    def odometry(self, namespace: str, topic: str = "odometry_sensor1/odometry") -> Odometry | None:
        """The last reading of the odometry sensor publishing /<namespace>/<topic>, read from the
        vehicle bus (what nav_msgs/Odometry carries), None before the first. SimError when no odometry
        sensor publishes there."""
        got = self._w.odometry_array(namespace, f"/{namespace}/{topic}")
        if got is None:
            return None
        count, a = got
        return Odometry(float(a[0]), a[1:4], a[4:8], a[8:11], a[11:14], count)

    def imu(self, namespace: str, topic: str = "imu") -> Imu | None:
        """The last reading of the IMU publishing /<namespace>/<topic>, read from the vehicle bus
        (the plugin puts it there every step, whether or not anyone listens), None before the first.
        SimError when no IMU publishes there."""
        got = self._w.imu_array(namespace, f"/{namespace}/{topic}")
        if got is None:
            return None
        count, a = got
        return Imu(float(a[0]), a[1:4], a[4:7], count)

    def listen(self, topics: Sequence[str] = ()) -> None:
        """Keep only these topics' messages (their plugins skip building the others): faster when a
        loop reads one or two topics. No argument: all again, except the cameras' images and
        camera_info, which are kept only when named here (building them costs a frame's render)."""
        self._w.listen(list(topics))

    def attach_controller(self, namespace: str, controller: Any, odometry_topic: str = "odometry_sensor1/odometry") -> None:
        """Runs `controller` (LeePositionController, AttitudeLevelController) in C++ inside step():
        each new odometry message of /<namespace>/<odometry_topic> is answered with a motor command
        before the next physics step, exactly as the Python loop (and a ROS node in lockstep) would."""
        self._w.attach_controller(namespace, f"/{namespace}/{odometry_topic}", controller.engine)

    def detach_controllers(self) -> None:
        self._w.detach_controllers()

    def camera_image(self, model: str, sensor: str, index: int = 0) -> np.ndarray:
        """The sensor's last frame (H x W x channels, uint8, rows top to bottom): a view of the
        engine's buffer, valid until the next step (copy it to keep it)."""
        return self._w.camera_image(model, sensor, index, False)

    def camera_depth(self, model: str, sensor: str, index: int = 0) -> np.ndarray:
        """The camera's last depth image [m] (H x W float32, NaN where nothing is in range), aligned with
        its image; a view, as camera_image. A plain camera (a VI-sensor's left or right) renders its
        ground-truth depth from the first ask on."""
        return self._w.camera_image(model, sensor, index, True)

    def laser_scan(self, model: str, sensor: str) -> dict:
        """The last scan of a ray sensor: ranges_m and intensities (vertical x horizontal, views),
        column_time_s, start_time_s, scan_count."""
        return self._w.laser_scan(model, sensor)

    def sensors(self, model: str) -> list[tuple[str, str]]:
        return self._w.sensor_names(model)
