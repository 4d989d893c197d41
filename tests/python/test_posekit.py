"""posekit from Python: meshes, devices, checks, correction of a pose and of a sequence, the same
vertices as the command line, options as keywords, bad input as exceptions with nothing written."""

import subprocess
import sys

import numpy as np
import pytest

import posekit
from conftest import cli, same_vertices


def test_read_mesh_gives_float64_vertices_and_int32_faces(arm):
    V, F = posekit.read_mesh(str(arm["rest"]))
    assert V.dtype == np.float64 and V.ndim == 2 and V.shape[1] == 3
    assert F.dtype == np.int32 and F.shape[1] == 3
    assert F.min() == 0 and F.max() == V.shape[0] - 1


def test_write_mesh_round_trips_exactly(arm, tmp_path):
    V, F = posekit.read_mesh(str(arm["bent"]))
    posekit.write_mesh(str(tmp_path / "copy.ply"), np.ascontiguousarray(V), F.astype(np.int64))
    V2, F2 = posekit.read_mesh(str(tmp_path / "copy.ply"))
    assert same_vertices(V, V2) and (F == F2).all()


def test_devices_lists_the_cpu_as_available():
    backends = {entry["name"]: entry for entry in posekit.devices()}
    assert set(backends) == {"cpu", "opencl", "vulkan", "cuda"}
    assert backends["cpu"]["state"] == "available"


def test_check_counts_new_intersections(arm):
    V_ref, F = posekit.read_mesh(str(arm["rest"]))
    V, _ = posekit.read_mesh(str(arm["bent"]))
    assert posekit.check(V_ref, F)["self_intersecting_faces"] == 0
    counts = posekit.check(V, F, reference=V_ref)
    assert counts["new_self_intersecting_faces"] > 0
    assert counts["faces"] == F.shape[0]


def test_correct_frees_the_arm_like_the_command_line(arm, tmp_path):
    V_ref, F = posekit.read_mesh(str(arm["rest"]))
    V, _ = posekit.read_mesh(str(arm["bent"]))
    stages = []
    V_out, report = posekit.correct(V_ref, V, F, device="cpu", progress=lambda stage, done: stages.append(stage))
    assert posekit.check(V_out, F, reference=V_ref)["new_self_intersecting_faces"] == 0
    assert report["result"]["intersecting_faces"]["new"] == 0
    assert [s["name"] for s in report["stages"]][0] == "field"
    assert "field" in stages
    out = tmp_path / "cli.obj"
    result = cli("correct", str(arm["rest"]), str(arm["bent"]), "-o", str(out), "--device", "cpu")
    assert result.returncode == 0, result.stderr
    assert same_vertices(V_out, posekit.read_mesh(str(out))[0])


def test_correct_takes_the_command_line_options_as_keywords(arm):
    V_ref, F = posekit.read_mesh(str(arm["rest"]))
    V, _ = posekit.read_mesh(str(arm["bent"]))
    _, report = posekit.correct(V_ref, V, F, device="cpu", whole_mesh=True, key_frames=7, no_halfway=True,
                                exclude=[0, 1])
    assert report["field"]["whole_mesh"] is True
    assert report["field"]["key_frames"] == 7
    assert next(s for s in report["stages"] if s["name"] == "halfway")["skipped"] == "disabled"
    with pytest.raises(ValueError, match="key_frames"):
        posekit.correct(V_ref, V, F, key_frames=1)
    with pytest.raises(ValueError, match="no_such_option"):
        posekit.correct(V_ref, V, F, no_such_option=3)


def test_help_explains_the_arguments():
    assert "V_target" in posekit.correct.__doc__ and "key_frames" in posekit.correct.__doc__
    assert "smoothing" in posekit.correct_sequence.__doc__


def test_bad_input_raises_value_error_and_writes_nothing(arm, tmp_path):
    V_ref, F = posekit.read_mesh(str(arm["rest"]))
    V, _ = posekit.read_mesh(str(arm["bent"]))
    with pytest.raises(ValueError, match="V_target"):
        posekit.correct(V_ref, V[:, :2], F)
    with pytest.raises(ValueError, match="V_target"):
        posekit.correct(V_ref, V.astype(str), F)
    with pytest.raises(ValueError, match="F"):
        posekit.correct(V_ref, V, F.astype(np.float64))
    nan = V.copy()
    nan[5, 1] = np.nan
    with pytest.raises(ValueError, match="finite"):
        posekit.correct(V_ref, nan, F)
    with pytest.raises(ValueError, match="vertices"):
        posekit.correct(V_ref, V[:-4], F)
    out = tmp_path / "bad.obj"
    with pytest.raises(ValueError):
        posekit.write_mesh(str(out), nan, F)
    with pytest.raises(ValueError):
        posekit.write_mesh(str(out), V, F + V.shape[0])
    assert not out.exists() and list(tmp_path.iterdir()) == []
    with pytest.raises(ValueError, match="nope.obj"):
        posekit.read_mesh(str(tmp_path / "nope.obj"))


def test_correct_sequence_matches_the_command_line(arm, tmp_path):
    V_ref, F = posekit.read_mesh(str(arm["rest"]))
    frames = [posekit.read_mesh(str(f))[0] for f in arm["frames"]]
    progress = []
    results, sequence = posekit.correct_sequence(V_ref, frames, F, device="cpu",
                                                 progress=lambda done, total: progress.append((done, total)))
    assert len(results) == len(frames) and sequence["frames"] == len(frames)
    assert sequence["frames_with_new_faces"] == 0
    assert progress[-1] == (len(frames), len(frames))
    folder = tmp_path / "sequence"
    result = cli("correct-sequence", str(arm["rest"]), *map(str, arm["frames"]), "-o", str(folder), "--device", "cpu")
    assert result.returncode == 0, result.stderr
    for (V_out, report), file in zip(results, arm["frames"]):
        assert report["new_faces"] == 0
        assert same_vertices(V_out, posekit.read_mesh(str(folder / file.name))[0]), file.name


def test_python_m_posekit_forwards_to_the_command_line():
    result = subprocess.run([sys.executable, "-m", "posekit", "--version"], capture_output=True, text=True)
    assert result.returncode == 0 and result.stdout.startswith("posekit ")


def test_lion_01_same_vertices_as_the_command_line(shared_data, tmp_path):
    reference, target = shared_data / "lion-poses/lion-reference.obj", shared_data / "lion-poses/lion-01.obj"
    V_ref, F = posekit.read_mesh(str(reference))
    V, _ = posekit.read_mesh(str(target))
    V_out, report = posekit.correct(V_ref, V, F, device="cpu")
    assert report["result"]["intersecting_faces"]["new"] == 0
    out = tmp_path / "lion-01.obj"
    result = cli("correct", str(reference), str(target), "-o", str(out), "--device", "cpu")
    assert result.returncode == 0, result.stderr
    assert same_vertices(V_out, posekit.read_mesh(str(out))[0])


def test_correct_releases_the_gil(arm):
    import threading
    import time

    V_ref, F = posekit.read_mesh(str(arm["rest"]))
    V, _ = posekit.read_mesh(str(arm["bent"]))
    worker = threading.Thread(target=posekit.correct, args=(V_ref, V, F), kwargs={"device": "cpu"})
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1
        time.sleep(0.002)
    worker.join()
    # Holding the GIL for the whole correction (a few hundred ms) would leave this thread a tick or two.
    assert ticks >= 10


def test_interpolate_like_the_command_line(arm, tmp_path):
    V0, F = posekit.read_mesh(str(arm["rest"]))
    V1, _ = posekit.read_mesh(str(arm["bent"]))
    stages = []
    V_mid, report = posekit.interpolate([V0, V1], F, 0.5, progress=lambda stage, done: stages.append((stage, done)))
    assert report["weights"] == [0.5, 0.5] and np.isfinite(V_mid).all()
    assert stages[0] == ("precomputation", 0.0) and stages[-1] == ("interpolation", 1.0)
    out = tmp_path / "mid.obj"
    result = cli("interpolate", str(arm["rest"]), str(arm["bent"]), "--weights", "0.5", "-o", str(out))
    assert result.returncode == 0, result.stderr
    assert same_vertices(V_mid, posekit.read_mesh(str(out))[0])
    several = posekit.interpolate([V0, V1], F, [[0.75, 0.25], 0.5], method="vertex")
    assert len(several) == 2
    assert np.allclose(several[1][0], 0.5 * (V0 + V1), atol=1e-12)
    with pytest.raises(ValueError):
        posekit.interpolate([V0, V1], F, [0.2, 0.3, 0.5])
    with pytest.raises(ValueError, match="method"):
        posekit.interpolate([V0, V1], F, 0.5, method="spline")


def test_deform_like_the_command_line(arm, tmp_path):
    V0, F = posekit.read_mesh(str(arm["rest"]))
    V1, _ = posekit.read_mesh(str(arm["bent"]))
    vertices = [0, V0.shape[0] // 3, V0.shape[0] // 2, V0.shape[0] - 1]
    positions = V1[vertices]
    stages = []
    V_out, report = posekit.deform([V0, V1], F, vertices, positions, eigenfunctions=10,
                                   progress=lambda stage, done: stages.append((stage, done)))
    assert stages == [("setup", 0.0), ("setup", 1.0), ("deformation", 0.0), ("deformation", 1.0)]
    assert V_out.shape == V0.shape and np.isfinite(V_out).all()
    assert "deformation" in report and "setup" in report
    constraints = tmp_path / "points.txt"
    constraints.write_text("".join(f"{v} {x!r} {y!r} {z!r}\n" for v, (x, y, z) in zip(vertices, positions)))
    out = tmp_path / "deformed.obj"
    result = cli("deform", "--examples", str(arm["rest"]), str(arm["bent"]), "--constraints", str(constraints),
                 "-o", str(out), "--eigenfunctions", "10")
    assert result.returncode == 0, result.stderr
    assert same_vertices(V_out, posekit.read_mesh(str(out))[0])
    with pytest.raises(ValueError, match="positions"):
        posekit.deform([V0, V1], F, vertices, positions[:2])
    with pytest.raises(ValueError):
        posekit.deform([V0, V1], F, [V0.shape[0]], positions[:1])


def test_deform_with_the_skeleton_dictionary(arm, tmp_path):
    V0, F = posekit.read_mesh(str(arm["rest"]))
    V1, _ = posekit.read_mesh(str(arm["bent"]))
    V2, _ = posekit.read_mesh(str(arm["frames"][2]))
    vertices = [0, V0.shape[0] // 3, V0.shape[0] // 2, V0.shape[0] - 1]
    cache = tmp_path / "skinning.txt"
    V_out, report = posekit.deform([V0, V1, V2], F, vertices, V2[vertices], dictionary="skeleton",
                                   skinning_cache=str(cache))
    assert report["setup"]["dictionary"] == "skeleton" and report["setup"]["bones"] >= 2
    assert cache.is_file() and np.isfinite(V_out).all()
    with pytest.raises(ValueError, match="dictionary"):
        posekit.deform([V0, V1], F, vertices, V1[vertices], dictionary="bones")
    with pytest.raises(ValueError, match="weights"):
        posekit.deform([V0, V1], F, vertices, V1[vertices], weights=np.ones((V0.shape[0], 1)), dictionary="skeleton")


def test_register_like_the_command_line(arm, tmp_path):
    V0, F = posekit.read_mesh(str(arm["rest"]))
    V1, _ = posekit.read_mesh(str(arm["bent"]))
    # The partial scan: the bent pose's faces on one side of its bounding box, renumbered.
    kept = F[(V1[F][:, :, 1] > np.median(V1[:, 1])).all(axis=1)]
    used = np.unique(kept)
    renumber = np.full(V1.shape[0], -1)
    renumber[used] = np.arange(used.size)
    scan_V, scan_F = V1[used], renumber[kept].astype(np.int32)
    features = [int(used[0]), int(used[used.size // 2]), int(used[-1])]
    positions = V1[features]
    stages = []
    V_out, report = posekit.register([V0, V1], F, scan_V, scan_F, features, positions, eigenfunctions=10,
                                     icp_iterations=2, progress=lambda stage, done: stages.append(stage))
    assert stages == ["setup", "setup", "registration", "registration"]
    assert V_out.shape == V0.shape and np.isfinite(V_out).all()
    assert len(report["correspondence_of_scan_vertices"]["mesh_vertex"]) == scan_V.shape[0]
    scan_file, feature_file, out = tmp_path / "scan.ply", tmp_path / "features.txt", tmp_path / "fitted.obj"
    posekit.write_mesh(str(scan_file), scan_V, scan_F)
    feature_file.write_text("".join(f"{v} {x!r} {y!r} {z!r}\n" for v, (x, y, z) in zip(features, positions)))
    result = cli("register", "--examples", str(arm["rest"]), str(arm["bent"]), "--scan", str(scan_file), "--features",
                 str(feature_file), "-o", str(out), "--eigenfunctions", "10", "--icp-iterations", "2")
    assert result.returncode == 0, result.stderr
    assert same_vertices(V_out, posekit.read_mesh(str(out))[0])
    with pytest.raises(ValueError, match="icp_iterations"):
        posekit.register([V0, V1], F, scan_V, scan_F, features, positions, icp_iterations=-1)
