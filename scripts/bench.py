#!/usr/bin/env python3
"""make bench: measures the engine, the closed loop (controllers in their own processes and in the
simulator's), start-up, the estimator, cameras, sweeps and a soak on this machine, and prints a table
(medians of runs, with their range) and a JSON line. `--only engine,closed_loop,...` runs some
sections (see SECTIONS); what cannot be measured here is printed with the reason."""

import csv
import json
import os
import re
import signal
import statistics
import subprocess
import sys
import time
from pathlib import Path

from rotors_evaluation import watchers
from rotors_evaluation.processes import restore_sigint, stop_process_group
from rotors_evaluation.ros_master import start_own_master

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "build" / "bench"
WS = ROOT / "build" / "ws"


def sh(cmd: list[str], **kw) -> str:
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw).stdout


def bench_urdf(lump_rotors: bool) -> Path:
    """The firefly with its odometry sensor; the motors hold the hover command for the whole run, so
    the controller interface's commandTimeout is off (there is no controller to send commands)."""
    text = sh(
        [
            "xacro",
            sh(["rospack", "find", "rotors_description"]).strip() + "/urdf/mav_generic_odometry_sensor.gazebo",
            "mav_name:=firefly",
            "namespace:=firefly",
            f"lump_rotors:={'true' if lump_rotors else 'false'}",
        ]
    )
    held = text.replace("<commandTimeout>2.0</commandTimeout>", "<commandTimeout>0</commandTimeout>")
    assert held != text, "the firefly's controller interface has no <commandTimeout>2.0</commandTimeout> any more"
    path = OUT / f"firefly_{'lumped' if lump_rotors else 'hinged'}.urdf"
    path.write_text(held)
    return path


def engine_only(urdf: Path, with_ros: bool, runs: int = 5) -> dict:
    """In-process engine benchmark; with_ros: plugins publish (a private master runs meanwhile)."""
    world = sh(["rospack", "find", "rotors_gazebo"]).strip() + "/worlds/basic.world"
    bench = ROOT / "build/ws/devel/lib/rotors_gazebo_plugins/rotors_engine_bench"
    cmd = [str(bench), world, str(urdf), "firefly", "0.001", "20", "543.3"] + (["--ros"] if with_ros else [])
    env, master = dict(os.environ), None
    if with_ros:
        OUT.mkdir(parents=True, exist_ok=True)
        master, port = start_own_master(env, OUT / "rosmaster.log")
        env["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    try:
        results = [json.loads(sh(cmd, env=env).splitlines()[-1]) for _ in range(runs)]
    finally:
        stop_process_group(master, 30)
    return {"steps_per_s": statistics.median(r["steps_per_s"] for r in results), "plugins": results[0]["plugins"]}


def rotorpy_python() -> Path:
    """RotorPy 3.0.0 in its own venv, with its batched extra (torchdiffeq, roma, opt-einsum) and PyTorch
    without its CUDA packages (torch --no-deps and its pure-Python dependencies, as `make rl-site`)."""
    venv = OUT / "rotorpy-venv"
    python = venv / "bin" / "python"
    check = [str(python), "-c", "import torch, torchdiffeq, roma, opt_einsum, rotorpy"]
    if not python.exists() or subprocess.run(check, capture_output=True).returncode != 0:
        pip = [str(venv / "bin" / "pip"), "install", "-q", "--disable-pip-version-check"]
        subprocess.run(["/usr/bin/python3", "-m", "venv", str(venv)], check=True)
        subprocess.run([*pip, "rotorpy==3.0.0"], check=True, stderr=subprocess.DEVNULL)
        torch_deps = "sympy mpmath networkx jinja2 markupsafe fsspec filelock typing-extensions".split()
        batched = ["torch==2.13.0", *torch_deps, "torchdiffeq", "roma", "opt-einsum"]
        subprocess.run([*pip, "--no-deps", *batched], check=True, stderr=subprocess.DEVNULL)
    return python


def rotorpy_hover_wall_s() -> float:
    """The same 20 s hover simulated by RotorPy (SE3 controller, 1 kHz), in its own venv."""
    out = subprocess.run(
        [str(rotorpy_python()), str(ROOT / "scripts" / "peers" / "rotorpy_hover.py")], capture_output=True, text=True, check=True, cwd=OUT
    ).stdout
    return float(out.split()[-1])


class Graph:
    """A private ROS master running `launch_cmd`; stopped with Ctrl-C semantics on exit."""

    def __init__(self, launch_args: list[str]):
        self.env = dict(os.environ, ROS_HOME=str(OUT / "ros"))
        self.env.pop("DISPLAY", None)
        (OUT / "ros").mkdir(parents=True, exist_ok=True)
        self.master, self.port = start_own_master(self.env, OUT / "ros" / "rosmaster.log")
        self.env["ROS_MASTER_URI"] = f"http://127.0.0.1:{self.port}"
        self.proc = subprocess.Popen(
            ["roslaunch", "-p", str(self.port), *launch_args],
            env=self.env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )

    def watch(self, name: str, *args: str) -> list[float]:
        """Runs a watcher (rotors_evaluation.watchers) against this graph; the numbers of its last line."""
        out = subprocess.run(watchers.command(name, *args), env=self.env, capture_output=True, text=True, timeout=600, check=True).stdout
        return [float(x) for x in out.strip().splitlines()[-1].split()]

    def __enter__(self) -> "Graph":
        return self

    def __exit__(self, *exc) -> None:
        for proc in (self.proc, self.master):
            if not stop_process_group(proc, 30):  # the figure is already taken
                print(f"bench: {proc.args[0]} ignored Ctrl-C for 30 s; killed", file=sys.stderr)


def closed_loop(lockstep: bool, in_process: bool = False) -> dict:
    """The hovering example as fast as possible (sim + Lee controller + hovering_example +
    robot_state_publisher); the controller in its own process or in the simulator's."""
    with Graph(
        [
            "rotors_gazebo",
            "mav_hovering_example.launch",
            "gui:=false",
            "real_time_factor:=0",
            f"lockstep:={'true' if lockstep else 'false'}",
            f"in_process:={'true' if in_process else 'false'}",
        ]
    ) as g:
        rtf = g.watch("rtf", "5", "605" if in_process else "105")[-1]
        info = sh(["rosnode", "info", "/gazebo"], env=g.env)
        pid = next(line.split()[1] for line in info.splitlines() if line.startswith("Pid:"))
        rss_kb = int(next(line for line in Path(f"/proc/{pid}/status").read_text().splitlines() if line.startswith("VmHWM")).split()[1])
        return {"real_time_factor": rtf, "sim_peak_rss_mb": rss_kb / 1024}


def closed_loop_with_estimator(in_process: bool = False) -> float:
    """The MSF example in lockstep: sim + pose_sensor estimator + Lee controller, from 80 s (after
    the initialisation, which the example's own node requests on the wall clock) for 20 s of sim
    time, or 200 s in process."""
    with Graph(
        [
            "rotors_gazebo",
            "mav_hovering_example_msf.launch",
            "gui:=false",
            "real_time_factor:=0",
            "lockstep:=true",
            "random_seed:=3",
            f"in_process:={'true' if in_process else 'false'}",
        ]
    ) as g:
        return g.watch("rtf", "80", "280" if in_process else "100")[-1]


def waypoint_flight_steps_per_s(world: str) -> float:
    """Engine steps per second (10 ms steps) while the firefly flies the power plant's waypoint file
    in `world`, lockstep, as fast as possible, sim time 30-60 s (the first waypoint goes out at 30 s;
    in the power plant the MAV then hits the structure and stays in contact with it, as the book says)."""
    waypoints = Path(sh(["rospack", "find", "rotors_gazebo"]).strip()) / "resource" / "example_waypoints_powerplant.txt"
    with Graph(
        [
            "rotors_gazebo",
            "mav_with_waypoint_publisher.launch",
            "gui:=false",
            "real_time_factor:=0",
            "lockstep:=true",
            f"world_name:={world}",
            f"waypoint_file:={waypoints}",
        ]
    ) as g:
        return g.watch("rtf", "30", "60")[-1] / 0.01


def vi_sensor_closed_loop(real_time_factor: str, world: str = "basic", sensor_realism: bool = False) -> float:
    """The hovering example with the VI-sensor (stereo 752 x 480 at 30 Hz, images subscribed),
    lockstep; real_time_factor "1" (RotorS' pacing) or "0" (as fast as possible); sensor_realism:
    every effect of the VI-sensor on. Sim s per wall s."""
    with Graph(
        [
            "rotors_gazebo",
            "mav_hovering_example_with_vi_sensor.launch",
            "gui:=false",
            "lockstep:=true",
            f"real_time_factor:={real_time_factor}",
            f"world_name:={world}",
            f"sensor_realism:={'true' if sensor_realism else 'false'}",
        ]
    ) as g:
        return g.watch("vi")[-1]


def camera_fps(world: str, shadows: bool = True) -> dict:
    """rotors_camera_bench: stereo pairs and depth frames rendered per second (one thread asking; the
    rig moves every frame, so the sun's shadow map is drawn again for each pair)."""
    package = Path(sh(["rospack", "find", "rotors_gazebo"]).strip())
    env = dict(os.environ, GAZEBO_MODEL_PATH=str(package / "models"))  # as the launch files set it
    out = sh(
        [str(WS / "devel" / "lib" / "rotors_core" / "rotors_camera_bench"), str(package / "worlds" / f"{world}.world"), "200"]
        + ([] if shadows else ["--no-shadows"]),
        env=env,
    )
    return json.loads(out.strip().splitlines()[-1])


IMAGE_SENSOR_PRESETS = ("off", "blur", "blur_subframes", "auto_exposure", "noise", "rolling_shutter", "all")


def sensor_realism(world: str = "powerplant") -> dict:
    """rotors_camera_bench --image-sensor: the VI-sensor's stereo pair through the image sensor model
    while the rig moves at 1 m/s and turns at 0.75 rad/s (best of 3 runs of 40 pairs per preset), and
    the VI hovering example paced and as fast as possible with sensor_realism off and on."""
    package = Path(sh(["rospack", "find", "rotors_gazebo"]).strip())
    env = dict(os.environ, GAZEBO_MODEL_PATH=str(package / "models"))
    fps, renders = {}, {}
    for preset in IMAGE_SENSOR_PRESETS:
        runs = []
        for _ in range(3):
            out = sh(
                [str(WS / "devel" / "lib" / "rotors_core" / "rotors_camera_bench"), str(package / "worlds" / f"{world}.world"), "40"]
                + ["--image-sensor", preset],
                env=env,
            )
            runs.append(json.loads(out.strip().splitlines()[-1]))
        best = max(runs, key=lambda r: r["stereo_pairs_per_s"])
        fps[preset] = 2.0 * best["stereo_pairs_per_s"]  # frames: two per pair
        renders[preset] = best["renders_per_frame"]
    rtf = {
        name: dict(
            paced=statistics.median(vi_sensor_closed_loop("1", "basic", on) for _ in range(3)),
            as_fast_as_possible=statistics.median(vi_sensor_closed_loop("0", "basic", on) for _ in range(3)),
        )
        for name, on in (("off", False), ("all", True))
    }
    return dict(world=world, vi_sensor_fps=fps, renders_per_frame=renders, vi_hover=rtf, imu_vibration=imu_vibration_cost())


def imu_vibration_cost(sim_s: float = 20.0) -> dict:
    """The hovering firefly at 1 kHz in a Python World (Lee controller attached), physics steps per
    wall second with its IMU's rotorVibration off and on (sensor_realism; the generic-odometry
    firefly has no camera, so only the IMU changes), best of 3."""
    import rotors_sim as rs

    def steps_per_s(on: bool) -> float:
        world = rs.World("basic", step_size=0.001)
        world.spawn_mav("firefly", random_seed=3, sensor_realism=on)
        lee = rs.LeePositionController.for_mav("firefly")
        world.attach_controller("firefly", lee)
        lee.set_point([0.0, 0.0, 1.0])
        world.step(1000)
        t0 = time.perf_counter()
        world.step(int(sim_s * 1000))
        return sim_s * 1000 / (time.perf_counter() - t0)

    return {name: max(steps_per_s(on) for _ in range(3)) for name, on in (("off", False), ("on", True))}


def ros2_closed_loop(runs: int = 3) -> dict:
    """The hovering example's closed loop on ROS 2 (scripts/ros2_rtf.py: the ROS 2 front end as fast
    as possible, an rclpy node subscribed to its odometry, IMU and ground truth) beside ROS 1's
    (closed_loop: lockstep, the controller in its own process, over ROS), sim 5 to 105 s, median of
    `runs` each, in the same run. Needs build/ros2-venv (make ros2-setup)."""
    if not (ROOT / "build" / "ros2-venv" / "bin" / "python").exists():
        return {"not_measured": "no build/ros2-venv: run make ros2-setup"}
    ros2 = []
    for _ in range(runs):
        out = sh(["bash", "-c", f"source {ROOT}/scripts/ros2_env.bash && python {ROOT}/scripts/ros2_rtf.py 5 105"])
        ros2.append(json.loads(out.strip().splitlines()[-1]))
    ros1 = [closed_loop(True)["real_time_factor"] for _ in range(runs)]
    best = max(ros2, key=lambda r: r["real_time_factor"])
    return {
        "ros2_real_time_factor": statistics.median(r["real_time_factor"] for r in ros2),
        "ros2_range": [min(r["real_time_factor"] for r in ros2), max(r["real_time_factor"] for r in ros2)],
        "ros2_received_of_10000": best["received"],
        "ros1_real_time_factor": statistics.median(ros1),
        "ros1_range": [min(ros1), max(ros1)],
    }


def ros2_rows(r: dict) -> list:
    if "not_measured" in r:
        return [("ROS 2 closed loop", "not measured: " + r["not_measured"], "")]
    ratio = r["ros2_real_time_factor"] / r["ros1_real_time_factor"]
    got = ", ".join(f"{k} {v:,}" for k, v in r["ros2_received_of_10000"].items())
    return [
        (
            "closed loop (hovering example), ROS 1, lockstep, controller in its own process",
            f"{r['ros1_real_time_factor']:.1f} ({r['ros1_range'][0]:.1f}-{r['ros1_range'][1]:.1f}) x real time",
            "",
        ),
        (
            "  the same on ROS 2 (Lee in the world's loop, an rclpy node subscribed to 3 sensor topics)",
            f"{r['ros2_real_time_factor']:.1f} ({r['ros2_range'][0]:.1f}-{r['ros2_range'][1]:.1f}) x real time, "
            f"{ratio:.2f} x ROS 1's; the subscriber took {got} of 10,000 readings each",
            ">= 0.5 x ROS 1's",
        ),
    ]


def sensor_realism_rows(r: dict) -> list:
    fps = r["vi_sensor_fps"]
    rows = [
        (
            f"VI-sensor frames, {r['world']}, moving 1 m/s and 0.75 rad/s, image sensor {preset}",
            f"{fps[preset]:.1f} frames/s ({r['renders_per_frame'][preset]:.1f} renders a frame, "
            f"{fps['off'] / fps[preset]:.2f} x the plain frame's cost)",
            "all: <= 2 x" if preset == "all" else "",
        )
        for preset in IMAGE_SENSOR_PRESETS
    ]
    v = r["imu_vibration"]
    rows.append(
        (
            "hovering firefly at 1 kHz (Python World), IMU rotorVibration off / on",
            f"{v['off']:,.0f} / {v['on']:,.0f} steps/s ({v['off'] / v['on']:.2f} x the cost)",
            "",
        )
    )
    for name in ("off", "all"):
        h = r["vi_hover"][name]
        rows.append(
            (
                f"VI hovering example, sensor_realism {'on' if name == 'all' else 'off'}, lockstep, paced / as fast as possible",
                f"{h['paced']:.2f} / {h['as_fast_as_possible']:.2f} x real time",
                ">= 1 paced" if name == "all" else "",
            )
        )
    return rows


def ray_caster() -> dict:
    """rotors_ray_bench in the power plant: the caster's rays per second against a bare Embree loop over
    the same rays and scene, and a VLP-16 / OS1-64 stepping with the world (no ROS, no controller)."""
    package = Path(sh(["rospack", "find", "rotors_gazebo"]).strip())
    env = dict(os.environ, GAZEBO_MODEL_PATH=str(package / "models"))
    out = sh([str(WS / "devel" / "lib" / "rotors_core" / "rotors_ray_bench"), str(package / "worlds" / "powerplant.world"), "20"], env=env)
    return json.loads(out.strip().splitlines()[-1])


def planning_pairs() -> dict:
    """rotors_planning_bench: 50 seeded start/goal pairs in the power plant's octree (points connected
    to the open sky, 5-40 m apart), the firefly's radius: success, planning time, length, clearance."""
    plant = Path(sh(["rospack", "find", "rotors_gazebo"]).strip()) / "resource" / "power_plant.bt"
    out = sh([str(WS / "devel" / "lib" / "rotors_planning" / "rotors_planning_bench"), str(plant), "50", "1"])
    return json.loads(out.strip().splitlines()[-1])


def lidar_closed_loop(lidar: str, in_process: bool) -> dict:
    """The hovering example with a lidar in the power plant (mav_hovering_example_with_lidar.launch),
    lockstep, as fast as possible, its cloud subscribed: sim s per wall s and clouds per sim s."""
    topic = {"vlp16": "/firefly/velodyne_points", "os1_64": "/firefly/os1/points"}[lidar]
    with Graph(
        [
            "rotors_gazebo",
            "mav_hovering_example_with_lidar.launch",
            "gui:=false",
            "lockstep:=true",
            "real_time_factor:=0",
            f"enable_lidar:={lidar}",
            f"in_process:={'true' if in_process else 'false'}",
        ]
    ) as g:
        clouds_per_sim_s, rtf = g.watch("lidar", topic)
        return {"clouds_per_sim_s": clouds_per_sim_s, "real_time_factor": rtf}


def estimator_cost_us() -> dict:
    out = sh([str(WS / "devel" / "lib" / "msf_updates" / "msf_ekf_bench")]).split()
    return {"imu_propagation_us": float(out[0]), "delayed_pose_update_us": float(out[1])}


def swarm_launch(n: int, in_process: bool = False) -> Path:
    """A launch file with n fireflies on a grid, each with its own Lee controller, all in lockstep;
    in_process: the controllers run in the simulator's process."""
    names = [f"firefly{i + 1}" for i in range(n)]
    blocks = []
    for i, name in enumerate(names):
        blocks.append(f"""  <group ns="{name}">
    <include file="$(find rotors_gazebo)/launch/spawn_mav.launch">
      <arg name="mav_name" value="firefly"/><arg name="namespace" value="{name}"/>
      <arg name="model" value="$(find rotors_description)/urdf/mav_generic_odometry_sensor.gazebo"/>
      <arg name="x" value="{(i % 5) * 2.0}"/><arg name="y" value="{(i // 5) * 2.0}"/>
    </include>
    <node name="lee_position_controller_node" pkg="rotors_control" type="lee_position_controller_node"
          args="{'--in-simulator' if in_process else ''}">
      <rosparam command="load" file="$(find rotors_gazebo)/resource/lee_controller_firefly.yaml"/>
      <rosparam command="load" file="$(find rotors_gazebo)/resource/firefly.yaml"/>
      <remap from="odometry" to="odometry_sensor1/odometry"/>
    </node>
  </group>
""")
    lock = ",".join(f"/{n}/command/motor_speed:/{n}/odometry_sensor1/odometry" for n in names)
    text = f"""<launch>
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <arg name="world_name" value="$(find rotors_gazebo)/worlds/basic.world"/>
    <arg name="paused" value="true"/><arg name="gui" value="false"/><arg name="real_time_factor" value="0"/>
    <arg name="lockstep_topics" value="{lock}"/>
  </include>
{''.join(blocks)}</launch>
"""
    path = OUT / f"swarm_{n}{'_in_process' if in_process else ''}.launch"
    path.write_text(text)
    return path


def launch_to_airborne(in_process: bool) -> dict:
    """Wall seconds from starting `roslaunch rotors_gazebo mav_hovering_example.launch` (paced at real
    time, as users run it; the master already up) until the firefly's ground truth is 0.2 m above
    the ground; the example itself waits 5 s of sim time before it sends the set point."""
    env = dict(os.environ, ROS_HOME=str(OUT / "ros"))
    env.pop("DISPLAY", None)
    master, port = start_own_master(env, OUT / "ros" / "rosmaster.log")
    env["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    watch = subprocess.Popen(
        watchers.command("airborne"), env=env, stdout=subprocess.PIPE, text=True, stderr=subprocess.DEVNULL, start_new_session=True
    )
    launch = None
    try:
        assert watch.stdout.readline().strip() == "ready"
        t0 = time.monotonic()
        launch = subprocess.Popen(
            [
                "roslaunch",
                "-p",
                str(port),
                "rotors_gazebo",
                "mav_hovering_example.launch",
                "gui:=false",
                f"in_process:={'true' if in_process else 'false'}",
            ],
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            start_new_session=True,
        )
        wall, sim = (float(x) for x in watch.stdout.readline().split())
        return {"wall_s": wall - t0, "sim_s": sim}
    finally:
        for proc in (watch, launch, master):
            stop_process_group(proc, 30)


def swarm_rtf(n: int, in_process: bool = False) -> float:
    """Sim seconds per wall second from 2 s of sim time on: 10 s, or in process (fast) 60 s and
    300 s for one firefly, so that the window lasts long enough on the wall clock to be measured."""
    end = 2.0 + ((300.0 if n == 1 else 60.0) if in_process else 10.0)
    with Graph([str(swarm_launch(n, in_process))]) as g:
        return g.watch("swarm", str(n), str(end))[-1]


def sweep_flights_per_hour(workers: int) -> dict:
    """The shipped firefly sweep (16 hovering flights of 20 s, lockstep) on local Ray with
    `workers` flights at a time: flights per wall hour, start-up of Ray included."""
    package = Path(sh(["rospack", "find", "rotors_evaluation"]).strip())
    out = OUT / f"sweep_{workers}"
    subprocess.run(["rm", "-rf", str(out)], check=True)
    t0 = time.monotonic()
    subprocess.run(
        [
            sys.executable,
            str(package / "scripts" / "sweep.py"),
            str(package / "sweeps" / "firefly_lee_gains_x_wind.yaml"),
            "-o",
            str(out),
            "--workers",
            str(workers),
        ],
        check=True,
        capture_output=True,
        timeout=1800,
    )
    wall_s = time.monotonic() - t0
    with open(out / "results.csv", newline="") as f:
        ok = sum(1 for row in csv.DictReader(f) if row["status"] == "ok")  # log tails span lines
    return {"flights": ok, "wall_s": wall_s, "flights_per_hour": 3600.0 * ok / wall_s}


def _proc_rss_cpu(pid: int) -> (float, float):
    """Resident set [MB] and CPU time (user + system) [s] of a process."""
    rss_kb = int(next(line for line in Path(f"/proc/{pid}/status").read_text().splitlines() if line.startswith("VmRSS")).split()[1])
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return rss_kb / 1024.0, (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def soak(sim_s: float = 3600.0, sample_every_s: float = 60.0) -> dict:
    """The 9-firefly swarm in lockstep for `sim_s` of sim time: the simulator's RSS and CPU seconds
    per sim second, sampled every `sample_every_s`, compared between the first and the last tenth."""
    with Graph(["rotors_gazebo", "firefly_swarm_hovering_example.launch", "gui:=false", "lockstep:=true", "real_time_factor:=0"]) as g:
        watch = subprocess.Popen(
            watchers.command("clock"), env=g.env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, start_new_session=True
        )
        try:
            pid = None
            samples = []  # (sim s, wall s, rss MB, cpu s)
            next_mark, w0 = sample_every_s, time.monotonic()
            stalled_since, last_t = time.monotonic(), -1.0
            for line in watch.stdout:
                t = float(line)
                if t > last_t:
                    stalled_since, last_t = time.monotonic(), t
                elif time.monotonic() - stalled_since > 120:
                    raise RuntimeError(f"soak: sim time stuck at {t:.1f} s for 120 s")
                if pid is None and t >= 0:
                    info = sh(["rosnode", "info", "/gazebo"], env=g.env)
                    pid = int(next(x.split()[1] for x in info.splitlines() if x.startswith("Pid:")))
                if pid is not None and t >= next_mark:
                    samples.append((t, time.monotonic() - w0, *_proc_rss_cpu(pid)))
                    next_mark += sample_every_s
                if t >= sim_s:
                    break
            hover = g.watch("soak_hover")[-1]
        finally:
            stop_process_group(watch, 5, signal.SIGKILL)
    tenth = max(1, len(samples) // 10)

    def cpu_per_sim_s(window):
        return (window[-1][3] - window[0][3]) / (window[-1][0] - window[0][0])

    def cpu_share(window):  # CPU seconds per wall second: the lockstep wait is part of it
        return (window[-1][3] - window[0][3]) / (window[-1][1] - window[0][1])

    first, last = samples[: tenth + 1], samples[-tenth - 1 :]
    return {
        "sim_s": samples[-1][0],
        "wall_s": samples[-1][1],
        "samples": len(samples),
        "rss_mb_first": first[0][2],
        "rss_mb_last": last[-1][2],
        "rss_mb_max": max(x[2] for x in samples),
        "cpu_ms_per_sim_s_first": 1000 * cpu_per_sim_s(first),
        "cpu_ms_per_sim_s_last": 1000 * cpu_per_sim_s(last),
        "cpu_share_first": cpu_share(first),
        "cpu_share_last": cpu_share(last),
        "hover_error_m_at_end": hover,
        "series_sim_s_wall_s_rss_mb_cpu_s": [[round(v, 3) for v in x] for x in samples],
    }


def soak_rows(k: dict) -> list:
    return [
        (
            "soak: 9 fireflies, lockstep, simulator RSS first / last / max",
            f"{k['rss_mb_first']:.0f} / {k['rss_mb_last']:.0f} / {k['rss_mb_max']:.0f} MB over {k['sim_s']:.0f} s sim "
            f"({k['wall_s'] / 60:.0f} min wall)",
            "flat",
        ),
        (
            "soak: simulator CPU per sim second, first / last tenth",
            f"{k['cpu_ms_per_sim_s_first']:.0f} / {k['cpu_ms_per_sim_s_last']:.0f} ms "
            f"(CPU seconds per wall second {k['cpu_share_first']:.2f} / {k['cpu_share_last']:.2f})",
            "flat",
        ),
        (
            "soak: the nine fireflies' largest height offset from 1.04 m at the end (their 1 m set points' hover height)",
            f"{k['hover_error_m_at_end'] * 1000:.1f} mm",
            "",
        ),
    ]


# The Python peers, each in a venv of its own under build/bench (pinned: crazyflow 0.0.2 runs with
# these versions of jax and mujoco; newer ones fail to build its model).
PEER_VENVS = {
    "pyflyt": ["pyflyt==0.29.0"],
    "crazyflow": ["crazyflow==0.0.2", "mujoco==3.3.7", "mujoco-mjx==3.3.7", "jax[cpu]==0.7.0", "numpy<2"],
    "crazyflow040": ["crazyflow==0.4.0"],  # its current release, with what it pulls in
    # what its CtrlAviary and DSL PID controller import (its pyproject also asks for stable-baselines3,
    # control, matplotlib and pytest, for learning, examples and tests); itself from a clone, below
    "gym_pybullet_drones": ["pybullet==3.2.7", "gymnasium==1.4.0", "numpy>=2.2,<3", "scipy>=1.15", "pillow", "transforms3d==0.4.2"],
}

# gym-pybullet-drones is not on PyPI: its README installs a clone (`pip install -e .`)
GYM_PYBULLET_DRONES_SRC = Path(os.environ.get("ROTORS_BENCH_GYM_PYBULLET_DRONES", OUT / "gym-pybullet-drones"))


def source_commit(src: Path) -> str:
    out = subprocess.run(["git", "-C", str(src), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    return out.stdout.strip() if out.returncode == 0 else "no git"


def peer_python(peer: str) -> Path:
    venv = OUT / f"{peer}-venv"
    stamp = venv / ".installed"
    want = " ".join(PEER_VENVS[peer])
    if peer == "gym_pybullet_drones":
        want += f" {GYM_PYBULLET_DRONES_SRC}@{source_commit(GYM_PYBULLET_DRONES_SRC)}"
    if not stamp.exists() or stamp.read_text() != want:
        print(f"[bench] installing {peer} into {venv} (once)", file=sys.stderr)
        pip = [str(venv / "bin" / "pip"), "install", "-q", "--disable-pip-version-check"]
        subprocess.run(["/usr/bin/python3", "-m", "venv", str(venv)], check=True)
        subprocess.run([*pip, *PEER_VENVS[peer]], check=True)
        if peer == "gym_pybullet_drones":
            subprocess.run([*pip, "--no-deps", "-e", str(GYM_PYBULLET_DRONES_SRC)], check=True)
        stamp.write_text(want)
    return venv / "bin" / "python"


def peer_available(peer: str) -> bool:
    return peer != "gym_pybullet_drones" or (GYM_PYBULLET_DRONES_SRC / "gym_pybullet_drones").is_dir()


def hover_drone_s_per_s(peer: str, worlds: int, seconds: float, rates_hz=(), mode: str = "") -> dict:
    """One closed-loop hover run of a peer script (scripts/peers/<peer>_hover.py): its JSON line.
    rates_hz: (physics, control) where the script takes them (gym-pybullet-drones), else 500 / 100;
    mode: "loop" or "one_call" for the scripts that have both (PEER_MODES)."""
    if peer in ("rotors_sim", "rotors_batch", "rotors_env"):
        python = sys.executable
    elif peer in ("rotorpy", "rotorpy_batch"):
        python = str(rotorpy_python())
    else:
        python = str(peer_python(peer))
    args = [str(worlds), str(seconds), *(str(hz) for hz in rates_hz), *([mode] if mode else [])]
    out = subprocess.run(
        [python, str(ROOT / "scripts" / "peers" / f"{peer}_hover.py"), *args], capture_output=True, text=True, timeout=1800, cwd=OUT
    )  # MuJoCo writes its log to cwd
    lines = [line for line in out.stdout.splitlines() if line.startswith("{")]
    if out.returncode != 0 or not lines:
        raise RuntimeError(f"{peer} hover ({worlds} worlds) failed: {(out.stderr or out.stdout)[-800:]}")
    return json.loads(lines[-1])


PYTHON_PEERS = (("rotors_sim", 20.0), ("crazyflow", 20.0), ("pyflyt", 5.0), ("gym_pybullet_drones", 5.0), ("rotorpy", 5.0))
# Each peer at its fastest documented use for the same task, and as a Python loop that computes the
# control each period. "loop": Python in the loop every control period; "one_call": one call runs
# many control periods with the simulator's own controller inside (where the simulator has one).
PEER_MODES = {"rotors_sim": ("loop", "one_call"), "crazyflow": ("loop", "one_call")}
NO_ONE_CALL = {
    "pyflyt": "no call that runs more than one control period (Aviary.step is one)",
    "gym_pybullet_drones": "no call that runs more than one control period (env.step is one)",
    "rotorpy": "its simulate() runs a whole flight but with the controller in Python each step",
}
MODE_WORDS = {
    "loop": "Python loop, control computed each period",
    "one_call": "one call, controller inside",
    "": "Python loop, control computed each period",
}


def python_peers() -> dict:
    """Hover, closed loop, 500 Hz physics and 100 Hz control, for 1 and 64 worlds, in each mode a
    peer has: best of 3 runs each."""
    table: dict = {}
    for peer, seconds in PYTHON_PEERS:
        if not peer_available(peer):
            continue
        for mode in PEER_MODES.get(peer, ("",)):
            for worlds in (1,) if peer == "rotorpy" else (1, 64):  # RotorPy: no batch of worlds
                slow = peer in ("pyflyt", "gym_pybullet_drones") or (peer == "rotors_sim" and mode == "loop")
                sim_s = seconds if worlds == 1 or not slow else 2.0
                runs = [hover_drone_s_per_s(peer, worlds, sim_s, mode=mode) for _ in range(3)]
                table[f"{peer}/{mode or 'loop'}/{worlds}"] = max(runs, key=lambda r: r["drone_s_per_s"])
    return table


def python_peer_rows(t: dict) -> list:
    rows = []
    notes = {
        "rotors_sim": "firefly, 12 RotorS plugins, Lee controller library, worlds on threads",
        "crazyflow": "Crazyflie, onboard state controller, JAX on the CPU (vmap over worlds)",
        "pyflyt": "QuadX in position mode; 64 = 64 drones in one Aviary (no batch of worlds)",
        "gym_pybullet_drones": f"CtrlAviary, Crazyflie 2.X, DSL PID controller, clone {source_commit(GYM_PYBULLET_DRONES_SRC)}; "
        "64 = 64 drones in one aviary (no batch of worlds)",
        "rotorpy": "SE3 controller at the physics rate, 500 Hz (no separate control rate); no batch of worlds",
    }
    for peer, _ in PYTHON_PEERS:
        for mode in PEER_MODES.get(peer, ("loop",)):
            one, many = t.get(f"{peer}/{mode}/1"), t.get(f"{peer}/{mode}/64")
            label = f"hover, 500 Hz physics, 100 Hz control: {peer}, {MODE_WORDS[mode]} ({notes[peer]})"
            if one is None:
                rows += [(label, "not measured", "")]
                continue
            many_text = f"{many['drone_s_per_s']:,.0f} drone-s/s" if many else "not run (no batch of worlds)"
            rows += [(label, f"1 world {one['drone_s_per_s']:,.1f} x real time; 64 worlds {many_text}", "")]
        if peer in NO_ONE_CALL:
            rows += [(f"  {peer}, one call: not measured", NO_ONE_CALL[peer], "")]

    def ratio(ours: str, theirs: str, digits: int = 2) -> str:
        return f"{t[ours]['drone_s_per_s'] / t[theirs]['drone_s_per_s']:,.{digits}f} x" if ours in t and theirs in t else "n/a"

    for mode in ("loop", "one_call"):
        rows += [
            (f"  ratio, one world, {MODE_WORDS[mode]}: rotors_sim / crazyflow", ratio(f"rotors_sim/{mode}/1", f"crazyflow/{mode}/1"), ""),
            (
                f"  ratio, 64 worlds, {MODE_WORDS[mode]}: rotors_sim / crazyflow (aggregate drone-s/s)",
                ratio(f"rotors_sim/{mode}/64", f"crazyflow/{mode}/64"),
                "",
            ),
        ]
    for peer in ("pyflyt", "gym_pybullet_drones"):
        rows += [(f"  ratio, one world, Python loop: rotors_sim / {peer}", ratio("rotors_sim/loop/1", f"{peer}/loop/1", 0), "")]
    return rows


# --- batched_flight: the batched flight engine against today's worlds and the peers ---------------
BATCH_COUNTS = (1, 64, 1024, 4096)
# (key in the JSON line, peer script, vehicle counts it runs, drone-seconds a run flies at most; each
# run flies at least 2 s of sim time). crazyflow: 20 s per world up to 64 worlds, as python_peers
# measures it (its rate changes with the length of one step call; 20 s gives its best here).
BATCH_PEERS = (
    ("rotors_batch", "rotors_batch", BATCH_COUNTS, 20000.0),
    ("rotors_world", "rotors_sim", (1, 64), 100.0),
    ("crazyflow==0.0.2", "crazyflow", BATCH_COUNTS, 20.0),
    ("crazyflow==0.4.0", "crazyflow040", BATCH_COUNTS, 20.0),
    ("gym_pybullet_drones", "gym_pybullet_drones", (1, 64), 40.0),
    ("PyFlyt", "pyflyt", (1, 64), 40.0),
    ("rotorpy", "rotorpy", (1,), 5.0),
    # RotorPy 3.0's batch (PyTorch, simulate_batch, rk4, one torch thread): 2 s of sim time at every count
    ("rotorpy_batch", "rotorpy_batch", (1, 64, 1024), 2.0),
)
BATCH_NOT_RUN = {
    "rotors_world": "a World per vehicle (xacro and 12 plugins each): 1,024 take minutes to build",
    "gym_pybullet_drones": "one aviary of N drones, slower than real time at 64",
    "PyFlyt": "one aviary of N drones, slower than real time at 64",
    "rotorpy": "its single-vehicle Environment; its batch is the rotorpy_batch row",
    "rotorpy_batch": "its whole flight's state history is kept in memory: 4,096 vehicles take about 5 GB",
}


def batch_profile() -> list[str]:
    """Where a one-vehicle batch spends its time: perf's self time per function (top 8)."""
    data = OUT / "batch_perf.data"
    script = ROOT / "scripts" / "peers" / "rotors_batch_hover.py"
    rec = subprocess.run(
        ["perf", "record", "-o", str(data), "-q", sys.executable, str(script), "1", "20000", "1"], capture_output=True, text=True
    )
    if rec.returncode != 0:
        return [f"no profile: perf record failed ({(rec.stderr or rec.stdout).strip()[-200:]})"]
    rep = subprocess.run(
        ["perf", "report", "-i", str(data), "--no-children", "--stdio", "--percent-limit", "2", "--sort", "symbol"],
        capture_output=True,
        text=True,
    )
    lines = [line.strip() for line in rep.stdout.splitlines() if line.strip() and line.strip()[0].isdigit()]
    return lines[:8]


def batched_flight() -> dict:
    """Hover, 500 Hz physics, 100 Hz control: drone-seconds per second of each simulator at each
    vehicle count (best of 3 runs), ours also on one thread and with the IMU, and a profile."""
    table: dict = {}
    for key, script, counts, drone_s in BATCH_PEERS:
        if not peer_available(script):
            continue
        for n in counts:
            sim_s = 20.0 if key.startswith("crazyflow") and n <= 64 else max(drone_s / n, 2.0 if n > 1 else drone_s)
            runs = [
                hover_drone_s_per_s(script, n, sim_s, mode="one_call" if script in ("rotors_sim", "crazyflow") else "") for _ in range(3)
            ]
            table.setdefault(key, {})[str(n)] = max(r["drone_s_per_s"] for r in runs)
    extra = {}
    for label, args in (
        ("one_thread_1024", ["1024", "20", "1"]),
        ("imu_1", ["1", "20000", "0", "imu"]),
        ("imu_64", ["64", "300", "0", "imu"]),
        ("randomized_1", ["1", "20000", "0", "no_imu", "randomized"]),
        ("randomized_64", ["64", "300", "0", "no_imu", "randomized"]),
    ):
        runs = [hover_drone_s_per_s("rotors_batch", int(args[0]), float(args[1]), rates_hz=args[2:]) for _ in range(3)]
        extra[label] = max(r["drone_s_per_s"] for r in runs)
    memory = hover_drone_s_per_s("rotors_batch", 1, 1.0)["memory_bytes_per_vehicle"]
    # the call an RL loop makes: FlightBatchEnv.step once per control period, beside the raw engine
    env = {}
    for n, sim_s in ((64, 4.0), (1024, 1.0)):
        for kind in ("nominal", "randomized"):
            runs = [hover_drone_s_per_s("rotors_env", n, sim_s, mode=kind) for _ in range(3)]
            env[f"{kind}_{n}"] = max(runs, key=lambda r: r["drone_s_per_s"])
    table["rotors_env"] = {str(n): env[f"randomized_{n}"]["drone_s_per_s"] for n in (64, 1024)}
    depth = max((batch_depth() for _ in range(3)), key=lambda r: r["rays_per_s"])
    table["depth"] = {k: depth[k] for k in ("vehicles", "rays_per_s", "caster_rays_per_s", "drone_s_per_s")}
    return {"table": table, "extra": extra, "memory": memory, "profile": batch_profile(), "env": env, "depth": depth}


POWER_PLANT_CENTRE = (15.0, -17.0)  # of the plant's footprint, x -5..35 m, y -35..0 m


def batch_depth(vehicles: int = 64, frames: int = 90) -> dict:
    """64 fireflies around the power plant, each with the 64 x 48 depth camera at 30 Hz (its frame
    every 16 steps of 1/480 s, Lee at 120 Hz): drone-s/s of the flight with its images, the depth
    images' rays per second, and the same rays cast by the project's packet caster (RayScene::CastFan
    through ObstacleField.cast, one vehicle per call, on as many threads as the batch has)."""
    from concurrent.futures import ThreadPoolExecutor

    import numpy as np

    import rotors_sim as rs
    from rotors_sim import _engine
    from rotors_sim.envs.batched import rotation_rows

    world = rs.World("powerplant")
    angle = np.arange(vehicles) * 2 * np.pi / vehicles
    cx, cy = POWER_PLANT_CENTRE
    positions = np.column_stack([cx + 25 * np.cos(angle), cy + 25 * np.sin(angle), np.full(vehicles, 5.0)])
    yaws = angle + np.pi  # facing the plant
    batch = rs.FlightBatch("firefly", count=vehicles, step_size=1 / 480, control_divisor=4, positions=positions, yaws=yaws)
    field = _engine.ObstacleField(vehicles, batch.collision_radius)
    field.set_world(world.engine, [cx, cy, 15.0], [80.0, 80.0, 30.0], 0.25)
    batch.set_obstacles(field)
    batch.set_depth_camera()
    cam = batch.depth_camera
    batch.step(480)  # hovering
    pixels = cam["width"] * cam["height"]
    t_depth = 0.0
    t0 = time.perf_counter()
    for _ in range(frames):
        batch.step(16)
        t1 = time.perf_counter()
        images = batch.render_depth()
        t_depth += time.perf_counter() - t1
    wall = time.perf_counter() - t0
    seen = float(np.isfinite(images).mean())
    # the same rays through the packet caster
    fx = cam["width"] / (2 * np.tan(cam["horizontal_fov"] / 2))
    fy = cam["height"] / (2 * np.tan(cam["vertical_fov"] / 2))
    u, v = np.meshgrid((np.arange(cam["width"]) - (cam["width"] - 1) / 2) / fx, (np.arange(cam["height"]) - (cam["height"] - 1) / 2) / fy)
    rays_M = np.column_stack([np.ones(pixels), -u.ravel(), -v.ravel()])
    rays_M /= np.linalg.norm(rays_M, axis=1, keepdims=True)
    truth = batch.truth()
    rotations = rotation_rows(truth[:, 3:7])
    jobs = [(i, truth[i, 0:3] + R @ np.asarray(cam["xyz"]), np.ascontiguousarray(rays_M @ R.T)) for i, R in enumerate(rotations)]
    far = cam["max_range"] * float(np.linalg.norm(rays_M, axis=1).max() / rays_M[:, 0].min())
    with ThreadPoolExecutor(batch.threads) as pool:
        t1 = time.perf_counter()
        for _ in range(10):
            list(pool.map(lambda job: field.cast(job[0], job[1], job[2], 0.0, far), jobs))
        t_caster = time.perf_counter() - t1
    return {
        "vehicles": vehicles,
        "rays_per_s": frames * vehicles * pixels / t_depth,
        "caster_rays_per_s": 10 * vehicles * pixels / t_caster,
        "drone_s_per_s": vehicles * frames * 16 / 480 / wall,
        "pixels_seen": seen,
        "threads": batch.threads,
    }


def batched_flight_rows(b: dict) -> list:
    t, x = b["table"], b["extra"]
    rows = []
    for key, _, counts, _ in BATCH_PEERS:
        if key not in t:
            rows += [(f"hover, 500 Hz physics, 100 Hz control: {key}", "not measured (not installed)", "")]
            continue
        figures = ", ".join(f"{n}: {t[key][str(n)]:,.0f}" for n in BATCH_COUNTS if str(n) in t[key])
        missing = [str(n) for n in BATCH_COUNTS if n not in counts]
        note = f"; {', '.join(missing)}: not run ({BATCH_NOT_RUN[key]})" if missing else ""
        rows += [(f"hover, 500 Hz physics, 100 Hz control, drone-s/s by vehicles: {key}", figures + note, "")]
    ours, yard = t.get("rotors_batch", {}), t.get("crazyflow==0.0.2", {})
    if ours and yard:
        fastest = {n: max(t[k][n] for k in ("crazyflow==0.0.2", "crazyflow==0.4.0") if k in t and n in t[k]) for n in ("1", "64")}
        rows += [
            ("  rotors_batch / crazyflow's faster release, 1 vehicle", f"{ours['1'] / fastest['1']:.1f} x", ">= 10 x"),
            ("  rotors_batch / crazyflow's faster release, 64 vehicles", f"{ours['64'] / fastest['64']:.1f} x", ">= 5 x"),
            (
                "  rotors_batch, every vehicle its own randomised airframe / crazyflow's faster release, 1 / 64 vehicles",
                f"{x['randomized_1'] / fastest['1']:.1f} x / {x['randomized_64'] / fastest['64']:.1f} x",
                ">= 10 x / >= 10 x",
            ),
        ]
    rotorpy_batch = t.get("rotorpy_batch", {})
    if ours and rotorpy_batch:
        ratios = {n: ours[n] / rotorpy_batch[n] for n in ("1", "64", "1024") if n in ours and n in rotorpy_batch}
        slower = [n for n, r in ratios.items() if r < 1.0]
        rows += [
            (
                "  rotors_batch / RotorPy's batch, 1 / 64 / 1,024 vehicles",
                " / ".join(f"{r:,.0f} x" for r in ratios.values()),
                "RotorPy's batch faster at " + ", ".join(slower) + " vehicles" if slower else "RotorPy's batch faster nowhere",
            )
        ]
    if ours:
        ns = {n: 1e9 / (ours[n] / 0.002) for n in ours}  # wall time per vehicle-step, both threads working
        rows += [
            (
                "  rotors_batch: wall time per vehicle-step, 64 / 1,024 / 4,096 vehicles (2 threads)",
                " / ".join(f"{ns[n]:.0f} ns" for n in ("64", "1024", "4096") if n in ns),
                "flat",
            ),
            ("  rotors_batch: 1,024 vehicles, 2 threads / 1 thread", f"{ours['1024'] / x['one_thread_1024']:.2f} x", "near 2 x"),
            (
                "  rotors_batch with the IMU and its noise (RotorS' vehicle as it flies), 1 / 64 vehicles",
                f"{x['imu_1']:,.0f} / {x['imu_64']:,.0f} drone-s/s",
                "",
            ),
        ]
    for n in (64, 1024):
        r, nominal = b["env"][f"randomized_{n}"], b["env"][f"nominal_{n}"]
        rows += [
            (
                f"  FlightBatchEnv.step (hover, motor actions), {n:,} vehicles, randomised airframes / the xacro's",
                f"{r['drone_s_per_s']:,.0f} / {nominal['drone_s_per_s']:,.0f} drone-s/s, "
                f"{r['env_steps_per_s']:,.0f} / {nominal['env_steps_per_s']:,.0f} env steps/s",
                "",
            ),
            (
                f"  FlightBatchEnv.step / the raw engine in the same mode (rotor speeds, one call), {n:,} vehicles",
                f"{r['drone_s_per_s'] / r['raw_drone_s_per_s']:.2f} x (raw {r['raw_drone_s_per_s']:,.0f} drone-s/s)",
                ">= 0.5 x" if n == 1024 else "",
            ),
        ]
    d = b["depth"]
    rows += [
        (
            f"  depth: {d['vehicles']} fireflies around the power plant, each a 64 x 48 depth camera at 30 Hz "
            f"({d['pixels_seen']:.0%} of the pixels see it), {d['threads']} threads",
            f"{d['drone_s_per_s']:,.0f} drone-s/s with the images; {d['rays_per_s'] / 1e6:.1f} M rays/s",
            "",
        ),
        (
            "  depth rays / the same rays through the packet caster (RayScene::CastFan)",
            f"{d['rays_per_s'] / d['caster_rays_per_s']:.2f} x (caster {d['caster_rays_per_s'] / 1e6:.1f} M rays/s)",
            ">= 0.75 x",
        ),
    ]
    m = b["memory"]
    rows += [
        (
            "  rotors_batch memory per vehicle: state arrays / Lee controller object / noise models",
            f"{m['state']} / {m['controller']} / {m['noise']} bytes",
            "state < 1 KB",
        )
    ]
    rows += [("  where one vehicle's step goes (perf, self time)", line, "") for line in b["profile"]]
    kernel = sum(float(line.split("%")[0]) for line in b["profile"] if any(k in line for k in ("StepLanes", "RotorLanes", "StepFreeBody")))
    rows += [
        (
            "  what bounds the next factor",
            f"one vehicle: the physics kernel ({kernel:.0f} % of the samples: its rotors in AVX-512 lanes, ODE's "
            "free-body step in scalar code, its force-free half beside the rotors) - what is left is one chain of "
            "dependent operations from the rotor forces to the next state (the sums in plugin order, then a square "
            "root and a division in turn), which lanes cannot shorten and fused multiply-add would change (ending "
            "the bit-for-bit equality with the full world); many: the kernel's eight AVX-512 lanes (about half of "
            "a step), the Lee controllers in lanes with the gathering of their inputs (about a quarter), and the "
            "per-vehicle passes for commands and sensors",
            "",
        )
    ]
    return rows


def betaflight_loop_rtf(lockstep: bool, sim_s: float = 10.0) -> float:
    """Betaflight's SITL answering the iris' states with nothing else in the loop (world.step, the
    interface's exchange, the firmware): x real time. lockstep: our lockstep build (16 gyro/PID loops
    per 2 ms state); else Betaflight's own build (its clock scaled to the state rate)."""
    import tempfile

    import rotors_sim as rs
    from rotors_sim.betaflight import BetaflightSitl, read_cli_file
    from rotors_sim.paths import resource

    world = rs.World("basic", step_size=0.002)
    world.spawn_mav("iris", random_seed=1, enable_betaflight_interface=True, betaflight_lockstep=lockstep)
    world.set_rc("iris", [1500, 1500, 1000, 1500, 1000, 1800])
    with BetaflightSitl(tempfile.mkdtemp(), read_cli_file(resource("betaflight_iris.cli")), lockstep=lockstep) as fc:
        if not lockstep:
            fc.wait_until_answering(world, "iris", step_s=0.002)
        start = time.monotonic()
        world.step(int(round(sim_s / 0.002)))
        return sim_s / (time.monotonic() - start)


def autopilot_flights() -> dict:
    """The autopilot figures: Betaflight's loop in lockstep and clock-scaled (betaflight_loop_rtf), its
    whole test flight in lockstep with the test's Python pilot (29 s of sim time), and the pymavlink
    controller flying the firefly on HIL_SENSOR through the MAVLink interface (12 s at 250 Hz,
    lockstep). The test runs are the tests themselves (-s)."""

    def run(selection: list[str]) -> str:
        return sh([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-s", *selection], cwd=ROOT)

    loop = {name: [betaflight_loop_rtf(lockstep) for _ in range(3)] for name, lockstep in (("lockstep", True), ("clock_scaled", False))}
    betaflight = [
        float(re.search(r"\(([\d.]+) x real time\)", run(["test/test_betaflight_sitl.py", "-k", "not bit_for_bit"])).group(1))
        for _ in range(3)
    ]
    px4 = [float(re.search(r"\((\d+) steps/s\)", run(["test/test_px4_mavlink.py", "-k", "controller"])).group(1)) for _ in range(3)]
    return {"betaflight_loop_rtf": loop, "betaflight_rtf": betaflight, "px4_pymavlink_steps_per_s": px4}


GYM_PYBULLET_DRONES_MISSING = (
    f"gym-pybullet-drones: not measured. It is not on PyPI; its README installs a clone. Clone "
    f"https://github.com/utiasDSL/gym-pybullet-drones into {GYM_PYBULLET_DRONES_SRC} (or point "
    "ROTORS_BENCH_GYM_PYBULLET_DRONES at a clone) and the bench installs it into a venv of its own"
)

SECTIONS = (
    "engine",
    "peers",
    "python_peers",
    "closed_loop",
    "swarm",
    "startup",
    "estimator",
    "waypoints",
    "cameras",
    "vi_sensor",
    "lasers",
    "planning",
    "autopilots",
    "sweep",
    "soak",
    "batched_flight",
    "sensor_realism",
    "ros2",
)


def median_of(runs: int, measure) -> dict:
    values = [measure() for _ in range(runs)]
    return {"median": statistics.median(values), "min": min(values), "max": max(values)}


def rng(m: dict, fmt: str = "{:.1f}") -> str:
    """median (min-max) of runs"""
    return f"{fmt.format(m['median'])} ({fmt.format(m['min'])}-{fmt.format(m['max'])})"


def main() -> int:
    restore_sigint()  # started as a background job, the ROS processes would ignore the Ctrl-C that stops them
    OUT.mkdir(parents=True, exist_ok=True)
    only = set(SECTIONS)
    if "--soak-only" in sys.argv:  # make bench runs it too; this runs it alone
        only = {"soak"}
    if "--only" in sys.argv:
        only = set(sys.argv[sys.argv.index("--only") + 1].split(","))
        unknown = only - set(SECTIONS)
        if unknown:
            print(f"bench: unknown section(s) {', '.join(sorted(unknown))}; the sections are {', '.join(SECTIONS)}", file=sys.stderr)
            return 2
    res: dict = {"not_measured": []}
    if only & {"peers", "python_peers"} and not peer_available("gym_pybullet_drones"):
        res["not_measured"].append(GYM_PYBULLET_DRONES_MISSING)  # why both sections' rows say "not measured"
    rows: list = []
    if "engine" in only:
        lumped_urdf = bench_urdf(lump_rotors=True)
        lumped = median_of(1, lambda: engine_only(lumped_urdf, with_ros=False)["steps_per_s"])
        hinged = engine_only(bench_urdf(lump_rotors=False), with_ros=False)["steps_per_s"]
        with_ros = engine_only(lumped_urdf, with_ros=True)["steps_per_s"]
        res.update(
            engine_steps_per_s_1ms_no_ros=lumped["median"],
            engine_steps_per_s_1ms_hinged_rotors=hinged,
            engine_steps_per_s_1ms_ros_publishing=with_ros,
        )
        rows += [
            (
                "engine, firefly with all plugins, 1 ms step, no ROS (rotors: kinematic joints)",
                f"{lumped['median']:,.0f} steps/s",
                ">= 200,000",
            ),
            ("  the same with hinged rotor bodies (lump_rotors:=false, round one's engine)", f"{hinged:,.0f} steps/s", ""),
            ("  the same, plugins publishing on ROS", f"{with_ros:,.0f} steps/s", ""),
        ]
    if "closed_loop" in only:
        inproc = median_of(3, lambda: closed_loop(True, in_process=True)["real_time_factor"])
        lock = [closed_loop(True) for _ in range(3)]
        free = [closed_loop(False) for _ in range(3)]
        sep = {
            "median": statistics.median(r["real_time_factor"] for r in lock),
            "min": min(r["real_time_factor"] for r in lock),
            "max": max(r["real_time_factor"] for r in lock),
        }
        res.update(
            closed_loop_rtf_lockstep_in_process=inproc["median"],
            closed_loop_rtf_lockstep=sep["median"],
            closed_loop_rtf_as_fast_as_possible=statistics.median(r["real_time_factor"] for r in free),
            sim_peak_rss_mb=max(r["sim_peak_rss_mb"] for r in lock + free),
        )
        rows += [
            (
                "closed loop (hovering example), lockstep, 10 ms, controller in the simulator (in_process:=true)",
                f"{rng(inproc, '{:.0f}')} x real time",
                ">= 300",
            ),
            ("  the same, controller in its own process (over ROS)", f"{rng(sep)} x real time", ">= 10"),
            (
                "  own process, no lockstep (the controller falls behind: not a valid flight)",
                f"{res['closed_loop_rtf_as_fast_as_possible']:.1f} x real time",
                "",
            ),
            ("simulator peak RSS, one firefly", f"{res['sim_peak_rss_mb']:.0f} MB", "<= 150 MB"),
        ]
    if "swarm" in only:
        inproc = {n: swarm_rtf(n, in_process=True) for n in (1, 5, 10, 20)}
        sep = {n: swarm_rtf(n) for n in (1, 5, 10, 20)}
        res.update(lockstep_rtf_by_fireflies_in_process=inproc, lockstep_rtf_by_fireflies=sep)
        for n in (1, 5, 10, 20):
            rows += [
                (
                    f"{n} firefl{'y' if n == 1 else 'ies'}, each with its Lee controller, lockstep: in process / own "
                    "processes (one run each)",
                    f"{inproc[n]:.1f} / {sep[n]:.1f} x real time",
                    ">= 20 (20 fireflies, in process)" if n == 20 else "",
                )
            ]
    if "peers" in only:
        rotorpy_s = rotorpy_hover_wall_s()
        res.update(rotorpy_20s_hover_1khz_wall_s=rotorpy_s, rotorpy_real_time_factor=20.0 / rotorpy_s)
        rows += [("RotorPy, 20 s hover, SE3 controller, 1 kHz (one run)", f"{20.0 / rotorpy_s:.2f} x real time", "")]
        if "engine_steps_per_s_1ms_no_ros" in res:
            rows += [
                (
                    "ratio: our engine at 1 ms / RotorPy at 1 kHz",
                    f"{res['engine_steps_per_s_1ms_no_ros'] / 1000.0 / (20.0 / rotorpy_s):.0f} x",
                    "",
                )
            ]
        if "closed_loop_rtf_lockstep_in_process" in res:
            rows += [
                (
                    "ratio: our closed loop in process (lockstep, 10 ms) / RotorPy (1 kHz)",
                    f"{res['closed_loop_rtf_lockstep_in_process'] / (20.0 / rotorpy_s):.0f} x",
                    "",
                )
            ]
        if not peer_available("gym_pybullet_drones"):
            rows += [("ratio to gym-pybullet-drones (hover, DSL PID)", "not measured", ">= 5 x")]
        else:  # its hover at its default rates and at ours (the basic world's 10 ms step, control every step)
            for physics_hz, control_hz in ((240, 48), (100, 100)):
                gpd = max(
                    (hover_drone_s_per_s("gym_pybullet_drones", 1, 20.0, (physics_hz, control_hz)) for _ in range(3)),
                    key=lambda r: r["drone_s_per_s"],
                )
                res[f"gym_pybullet_drones_rtf_{physics_hz}_{control_hz}_hz"] = gpd["drone_s_per_s"]
                rows += [
                    (
                        f"gym-pybullet-drones, 20 s hover, DSL PID, {physics_hz} Hz physics, {control_hz} Hz " "control (best of 3)",
                        f"{gpd['drone_s_per_s']:.1f} x real time",
                        "",
                    )
                ]
                if "closed_loop_rtf_lockstep_in_process" in res:
                    rows += [
                        (
                            f"ratio: our closed loop in process (lockstep, 10 ms) / gym-pybullet-drones at "
                            f"{physics_hz}/{control_hz} Hz",
                            f"{res['closed_loop_rtf_lockstep_in_process'] / gpd['drone_s_per_s']:.1f} x",
                            ">= 5 x",
                        )
                    ]
    if "autopilots" in only:
        a = res["autopilots"] = autopilot_flights()
        lock, scaled = a["betaflight_loop_rtf"]["lockstep"], a["betaflight_loop_rtf"]["clock_scaled"]
        rows += [
            (
                "Betaflight 4.6 SITL loop, iris, 2 ms step, lockstep build (16 gyro/PID loops per state, each " "state answered)",
                f"{min(lock):.1f}-{max(lock):.1f} x real time",
                ">= 10 x",
            ),
            (
                "Betaflight 4.6 SITL loop, Betaflight's own build (its clock scaled to the state rate)",
                f"{min(scaled):.2f}-{max(scaled):.2f} x real time",
                "",
            ),
            (
                "Betaflight test flight (lockstep) with the test's Python pilot, 29 s of sim time",
                f"{min(a['betaflight_rtf']):.1f}-{max(a['betaflight_rtf']):.1f} x real time",
                "",
            ),
            (
                "pymavlink controller on HIL_SENSOR through the MAVLink interface, firefly, 4 ms step, lockstep "
                "(TCP, one round trip a step)",
                f"{min(a['px4_pymavlink_steps_per_s']):,.0f}-" f"{max(a['px4_pymavlink_steps_per_s']):,.0f} steps/s",
                "",
            ),
        ]
    if "batched_flight" in only:
        b = batched_flight()
        res["batched_flight"] = b["table"]
        res["batched_flight_details"] = {k: v for k, v in b.items() if k != "table"}
        rows += batched_flight_rows(b)
    if "python_peers" in only:
        res["python_peers"] = python_peers()
        rows += python_peer_rows(res["python_peers"])
    if "startup" in only:
        runs = {ip: [launch_to_airborne(ip) for _ in range(3)] for ip in (False, True)}
        res["launch_to_airborne"] = runs
        for ip, rs in runs.items():
            wall = statistics.median(r["wall_s"] for r in rs)
            over = [r["wall_s"] - r["sim_s"] for r in rs]
            rows += [
                (
                    f"roslaunch mav_hovering_example.launch to airborne (z > 0.2 m), real time{', in process' if ip else ''}",
                    f"{wall:.1f} s wall, {statistics.median(over):.1f} s ({min(over):.1f}-{max(over):.1f}) beyond the "
                    f"{statistics.median(r['sim_s'] for r in rs):.2f} s of sim time",
                    "< 3 s + 5 s sim",
                )
            ]
    if "estimator" in only:
        est_cost = estimator_cost_us()
        est_rtf = median_of(3, closed_loop_with_estimator)
        est_rtf_in = median_of(3, lambda: closed_loop_with_estimator(in_process=True))
        res.update(
            estimator=est_cost,
            closed_loop_rtf_lockstep_with_estimator=est_rtf["median"],
            closed_loop_rtf_lockstep_with_estimator_in_process=est_rtf_in["median"],
        )
        rows += [
            ("estimator: IMU propagation (15-state EKF)", f"{est_cost['imu_propagation_us']:.1f} us", ""),
            ("estimator: pose 100 ms late, update + re-propagation of 10 states", f"{est_cost['delayed_pose_update_us']:.1f} us", ""),
            (
                "closed loop with the estimator (sim + MSF + Lee controller), lockstep, in process",
                f"{rng(est_rtf_in, '{:.0f}')} x real time",
                "",
            ),
            ("  the same, estimator and controller in their own processes", f"{rng(est_rtf)} x real time", ""),
        ]
    if "waypoints" in only:
        flight_steps = {world: statistics.median(waypoint_flight_steps_per_s(world) for _ in range(3)) for world in ("basic", "powerplant")}
        res["waypoint_flight_steps_per_s"] = flight_steps
        rows += [
            (f"power plant waypoint file flown in the {world} world, lockstep, 10 ms (engine steps/s)", f"{steps:,.0f} steps/s", "")
            for world, steps in flight_steps.items()
        ]
        rows += [("ratio: power plant world / basic world", f"{flight_steps['powerplant'] / flight_steps['basic']:.0%}", ">= 50 %")]
    if "cameras" in only:
        cameras = {
            f"{world}{'' if shadows else '_no_shadows'}": camera_fps(world, shadows)
            for world in ("basic", "powerplant", "warehouse")
            for shadows in (True, False)
        }
        res["camera_fps"] = cameras
        for key, fps in cameras.items():
            world, _, shadows = key.partition("_no_")
            label = f"{world} world, {'no shadows' if shadows else 'shadows'}"
            rows += [
                (f"VI-sensor stereo pair, 2 x 752 x 480 L8 with noise, {label}", f"{fps['stereo_pairs_per_s']:.1f} pairs/s", ""),
                (f"depth camera, 640 x 480 with depth read back, {label}", f"{fps['depth_frames_per_s']:.0f} frames/s", ""),
            ]
    if "vi_sensor" in only:
        for world in ("basic", "powerplant"):
            vi_paced = statistics.median(vi_sensor_closed_loop("1", world) for _ in range(3))
            vi_fast = statistics.median(vi_sensor_closed_loop("0", world) for _ in range(3))
            res[f"vi_sensor_closed_loop_{world}"] = dict(rtf_paced=vi_paced, rtf_as_fast_as_possible=vi_fast)
            rows += [
                (
                    f"hovering example with the VI-sensor (stereo at 30 Hz), {world} world, lockstep, paced " "at real time",
                    f"{vi_paced:.2f} x real time",
                    ">= 1",
                ),
                ("the same, as fast as possible", f"{vi_fast:.2f} x real time", ">= 2"),
            ]
    if "lasers" in only:
        caster = ray_caster()
        loops = {(lidar, ip): lidar_closed_loop(lidar, ip) for lidar in ("vlp16", "os1_64") for ip in (True, False)}
        res.update(
            ray_caster_power_plant=caster,
            lidar_closed_loop={f"{lidar}{'_in_process' if ip else ''}": r for (lidar, ip), r in loops.items()},
        )
        rows += [
            (
                "ray caster in the power plant, one ray per call (VLP-16 beams from 5 places, one thread)",
                f"{caster['caster_rays_per_s'] / 1e6:.1f} M rays/s",
                "",
            ),
            (
                "  Embree's own figure, same rays and scene (bare rtcIntersect1 loop)",
                f"{caster['embree_rays_per_s'] / 1e6:.1f} M rays/s ({caster['caster_over_embree']:.0%} reached)",
                "",
            ),
            (
                "  the caster the sensors use: a column of 16 beams per Embree packet (rtcIntersect16)",
                f"{caster['caster_fan_rays_per_s'] / 1e6:.1f} M rays/s",
                "",
            ),
            (
                "  the power plant with a VLP-16 / an OS1-64 sweeping, no ROS, no controller",
                f"{caster['world_with_vlp16_sim_s_per_wall_s']:.1f} / {caster['world_with_os1_64_sim_s_per_wall_s']:.1f}" " x real time",
                "",
            ),
        ]
        for lidar, label, target in (("vlp16", "VLP-16 (16 x 1800, 10 Hz)", ">= 20"), ("os1_64", "OS1-64 (64 x 1024, 10 Hz)", ">= 5")):
            r_in, r_own = loops[(lidar, True)], loops[(lidar, False)]
            rows += [
                (
                    f"closed loop in the power plant with a {label}, lockstep, cloud subscribed: controller in " "process / own process",
                    f"{r_in['real_time_factor']:.1f} / {r_own['real_time_factor']:.1f} x "
                    f"real time ({r_in['clouds_per_sim_s']:.1f} clouds per sim s)",
                    target,
                )
            ]
    if "planning" in only:
        plan = planning_pairs()
        res["planning_power_plant"] = {k: v for k, v in plan.items() if k != "pairs"}
        rows += [
            (
                "planner in the power plant: 50 seeded start/goal pairs (5-40 m apart), firefly radius "
                f"{plan['radius_m']:.3f} m + 0.25 m margin: solved",
                f"{plan['success_rate']:.0%}",
                "",
            ),
            (
                "  planning time, median / largest (OMPL RRT-Connect + shortening, one thread)",
                f"{plan['median_time_s'] * 1e3:.1f} / {plan['max_time_s'] * 1e3:.1f} ms",
                "",
            ),
            (
                f"  path length over the straight line, the {plan['straight_blocked']} pairs whose line is blocked: " "median / largest",
                f"{plan['median_length_ratio_blocked']:.2f} / {plan['max_length_ratio']:.2f}",
                "",
            ),
            (
                "  smallest clearance of any trajectory to the plant (sampled every 10 ms)",
                f"{plan['smallest_clearance_m']:.3f} m",
                f">= {plan['radius_m']:.3f} (radius)",
            ),
        ]
    if "sweep" in only:
        sweeps = {n: sweep_flights_per_hour(n) for n in (1, 2)}
        res["sweep_firefly_lee_gains_x_wind"] = sweeps
        rows += [
            (
                f"sweep.py, shipped firefly sweep (16 x 20 s hovering flights), local Ray, {n} worker" f"{'s' if n > 1 else ''}",
                f"{r['flights_per_hour']:,.0f} flights/h ({r['flights']} in {r['wall_s']:.0f} s)",
                "",
            )
            for n, r in sweeps.items()
        ]
    if "sensor_realism" in only:
        res["sensor_realism"] = sensor_realism()
        rows += sensor_realism_rows(res["sensor_realism"])
        res["not_measured"].append(
            "sensor_realism vi_sensor_fps.vibration: the IMU's vibration is not in a camera frame's path; "
            "its cost is imu_vibration_steps_per_s"
        )
    if "ros2" in only:
        res["ros2"] = ros2_closed_loop()
        rows += ros2_rows(res["ros2"])
    if "soak" in only:
        soaked = soak(float(os.environ.get("SOAK_SIM_S", "3600")))
        res["soak_9_fireflies_lockstep"] = soaked
        rows += soak_rows(soaked)
    w = [max(len(r[i]) for r in rows) for i in range(3)]
    print(f"{'measurement'.ljust(w[0])}  {'median (range)'.ljust(w[1])}  target")
    for r in rows:
        print(f"{r[0].ljust(w[0])}  {r[1].ljust(w[1])}  {r[2]}")
    for line in res["not_measured"]:
        print(line)
    if only == {"batched_flight"}:  # the section alone ends with its own line
        print(json.dumps({"batched_flight": res["batched_flight"]}))
    elif only == {"sensor_realism"}:
        r = res["sensor_realism"]
        print(
            json.dumps(
                {
                    "sensor_realism": {
                        "vi_sensor_fps": {
                            **{k: r["vi_sensor_fps"][k] for k in ("off", "blur", "auto_exposure", "noise", "rolling_shutter", "all")},
                            "vibration": None,
                        },
                        "imu_vibration_steps_per_s": r["imu_vibration"],
                        "vi_hover_real_time_factor": {k: r["vi_hover"][k]["as_fast_as_possible"] for k in ("off", "all")},
                    }
                }
            )
        )
    else:
        print(json.dumps(res))
    return 0


if __name__ == "__main__":
    sys.exit(main())
