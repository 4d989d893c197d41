"""Fixtures of the posekit pytest suite: the command-line tool, the generated arm, the shared poses."""

import os
import pathlib
import subprocess

import pytest

import posekit


def cli(*arguments: str) -> subprocess.CompletedProcess:
    """Runs the build's posekit command-line tool."""
    return subprocess.run([os.environ.get("POSEKIT_CLI", "posekit"), *arguments], capture_output=True, text=True)


@pytest.fixture(scope="session")
def arm(tmp_path_factory):
    """The generated arm: its rest pose, and its bends from 30 to 80 degrees and back, as files."""
    folder = tmp_path_factory.mktemp("arm")
    angles = ["30", "45", "60", "70", "75", "80", "78", "72", "65", "50", "35"]
    result = cli("generate", "--output-dir", str(folder), "--angles", *angles, "135")
    assert result.returncode == 0, result.stderr
    frames = [folder / f"arm-bent-{int(a):03d}.obj" for a in angles]
    return {"rest": folder / "arm-rest.obj", "bent": folder / "arm-bent-135.obj", "frames": frames}


@pytest.fixture(scope="session")
def shared_data():
    """The real pose sets, or a skip when they are not on this machine."""
    folder = pathlib.Path(os.environ.get("POSEKIT_SHARED_DATA", "../shared/data"))
    if not (folder / "lion-poses").is_dir():
        pytest.skip(f"the shared poses are not in {folder}")
    return folder


def same_vertices(a, b) -> bool:
    return a.shape == b.shape and bool((a == b).all())


assert posekit  # the package under test is importable from PYTHONPATH
