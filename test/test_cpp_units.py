"""Runs every C++ gtest binary of the workspace (devel/lib/<pkg>/test_*) as one pytest case each."""
import subprocess
from pathlib import Path

import pytest

from conftest import WS

GTESTS = sorted(p for p in (WS / "devel" / "lib").glob("*/test_*") if p.is_file() and p.stat().st_mode & 0o111)


def test_gtest_binaries_exist():
    assert GTESTS, "no gtest binaries under build/ws/devel/lib: was `catkin_make tests` run?"


@pytest.mark.parametrize("binary", GTESTS, ids=[f"{p.parent.name}/{p.name}" for p in GTESTS])
def test_gtest(binary: Path):
    src_test_dir = WS / "src" / binary.parent.name / "test"
    res = subprocess.run([str(binary)], cwd=src_test_dir if src_test_dir.is_dir() else None,
                         capture_output=True, text=True, timeout=900)
    failed = [l for l in res.stdout.splitlines() if "[  FAILED  ]" in l]
    assert res.returncode == 0, "\n".join(failed) + "\n" + res.stdout[-4000:] + res.stderr[-2000:]
