"""The captured crane sequence (crane-0000 ... crane-0174 against crane-0014) corrected on a
LocalCluster of two worker processes: every frame bit-identical to `posekit correct-sequence`.
Part of the real-data suite (`ctest --preset realdata`, which sets POSEKIT_REALDATA=1)."""

import os

import pytest

import posekit
from conftest import cli, same_vertices

pytestmark = pytest.mark.skipif(os.environ.get("POSEKIT_REALDATA") != "1",
                                reason="real-data suite only (POSEKIT_REALDATA=1)")


def test_crane_sequence_on_two_workers_as_the_command_line(shared_data, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    folder = shared_data / "crane-sequence"
    files = [folder / f"crane-{t:04d}.obj" for t in range(175)]
    if not all(f.exists() for f in files):
        pytest.skip(f"the crane sequence is not in {folder}")
    V_ref, F = posekit.read_mesh(str(folder / "crane-0014.obj"))
    frames = [posekit.read_mesh(str(f))[0] for f in files]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            results = posekit.distributed.correct_sequence(V_ref, frames, F, client=client, device="cpu")
    out = tmp_path / "crane"
    result = cli("correct-sequence", str(folder / "crane-0014.obj"), *map(str, files), "-o", str(out), "--device", "cpu")
    assert result.returncode == 0, result.stderr
    assert len(results) == len(files)
    for (V, report), file in zip(results, files):
        assert report["new_faces"] == 0, file.name
        assert same_vertices(V, posekit.read_mesh(str(out / file.name))[0]), file.name
