"""Runs every C++ gtest binary the CMakeLists declare (catkin_add_gtest) as one pytest case each.
The list is pinned: a binary that silently vanishes (no googletest, a CMake mistake) fails here, and so
does one that runs another number of tests than it holds today (a test that vanishes, or one added
without raising its pin)."""

import platform
import re
import subprocess

import pytest

from support import REPO, WS

# binary (devel/lib/<package>/<name>) -> the number of tests it holds; change it when you add or remove tests
GTESTS = {
    "mav_msgs_api_user/test_mav_msgs_api": 11,
    "msf_updates/test_msf_pose_ekf": 10,
    "rotors_control_api_user/test_rotors_control_api": 5,
    "rotors_control/test_rotors_control": 21,
    "rotors_core/test_rotors_core_engine": 79,
    "rotors_gazebo_plugins/test_autopilot_codecs": 16,
    "rotors_gazebo_plugins/test_rotors_gazebo_plugins_models": 74,
    "rotors_planning/test_rotors_planning": 9,
    "rotors_flight_batch/test_flight_kernel": 5,
}


def test_every_declared_gtest_is_listed():
    declared = set()
    for cmake in REPO.rglob("CMakeLists.txt"):
        if "build" in cmake.relative_to(REPO).parts:
            continue
        declared |= set(re.findall(r"catkin_add_gtest\(\s*(\w+)", cmake.read_text()))
    assert declared == {name.split("/")[1] for name in GTESTS}


@pytest.mark.parametrize("name", sorted(GTESTS))
def test_gtest(name: str):
    binary = WS / "devel" / "lib" / name
    assert binary.is_file(), f"{binary} was not built: is googletest installed, and did `catkin_make tests` run?"
    src_test_dir = WS / "src" / binary.parent.name / "test"
    res = subprocess.run([str(binary)], cwd=src_test_dir if src_test_dir.is_dir() else None, capture_output=True, text=True, timeout=900)
    failed = [line for line in res.stdout.splitlines() if "[  FAILED  ]" in line]
    assert res.returncode == 0, "\n".join(failed) + "\n" + res.stdout[-4000:] + res.stderr[-2000:]
    passed = re.search(r"\[  PASSED  \] (\d+) tests?", res.stdout)
    assert passed and int(passed.group(1)) == GTESTS[name], f"{name}: {passed and passed.group(0)}, pinned {GTESTS[name]}"


def test_no_function_compiled_for_avx_stands_in_for_a_baseline_one():
    """The kernels' AVX-512 and AVX2 files are compiled for those sets. A function they emit with
    vague linkage (an inline function or a template instantiation not inlined) could be the copy the
    linker keeps for every caller, and a CPU without the set would then fault in baseline code. Each
    such symbol of theirs must therefore be an instantiation on their own lane type (`__vector`)."""
    objects = sorted((WS / "build" / "rotors_flight_batch").rglob("flight_kernel_avx*.cpp.o"))
    x86 = platform.machine() in ("x86_64", "AMD64", "amd64")
    # CMake compiles the AVX files for x86-64 only (rotors_flight_batch/CMakeLists.txt)
    assert len(objects) == (2 if x86 else 0), [o.name for o in objects]
    for obj in objects:
        res = subprocess.run(["nm", "-C", str(obj)], capture_output=True, text=True, timeout=60, check=True)
        weak = [line for line in res.stdout.splitlines() if re.match(r"^[0-9a-f]+ [WV] ", line)]
        shared = [line for line in weak if "__vector" not in line]
        assert not shared, f"{obj.name} emits functions any caller may get: {shared}"
        print(f"{obj.name}: {len(weak)} vague-linkage functions, each on its lane type")
