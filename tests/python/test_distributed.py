"""posekit.distributed on a LocalCluster of two worker processes: the same frames, bit for bit, as
posekit.correct_sequence on one machine, in order, each once, also when a worker dies mid-run."""

import os
import signal
import threading
import time

import pytest

import posekit

distributed = pytest.importorskip("dask.distributed")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as connected:
            yield connected


@pytest.fixture(scope="module")
def sequence(arm):
    V_ref, F = posekit.read_mesh(str(arm["rest"]))
    frames = [posekit.read_mesh(str(f))[0] for f in arm["frames"]]
    alone, _ = posekit.correct_sequence(V_ref, frames, F, device="cpu")
    return V_ref, frames, F, alone


def expect_same(results, alone):
    assert len(results) == len(alone)
    for t, ((V, report), (V_alone, report_alone)) in enumerate(zip(results, alone)):
        assert V.shape == V_alone.shape and (V == V_alone).all(), f"frame {t}"
        for key in ("corrected", "carried", "carried_scale", "new_faces", "own_share", "distance_to_target", "reused"):
            assert report[key] == report_alone[key], f"frame {t}: {key}"


def test_same_frames_as_one_machine(client, sequence):
    V_ref, frames, F, alone = sequence
    progress = []
    results = posekit.distributed.correct_sequence(V_ref, frames, F, client=client, chunk_frames=2, device="cpu",
                                                   progress=lambda done, total: progress.append((done, total)))
    expect_same(results, alone)
    assert progress[-1] == (len(frames), len(frames))
    assert [done for done, _ in progress] == sorted(done for done, _ in progress)


def test_a_worker_killed_mid_run_costs_a_retry_not_a_frame(client, sequence):
    V_ref, frames, F, alone = sequence
    killed = []

    def kill_a_correcting_worker():
        # Waits for a worker to be correcting frames (the first pass), then kills its process.
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            for worker, tasks in client.processing().items():
                if any(str(task).startswith("_own_corrections") for task in tasks):
                    pid = client.run(os.getpid, workers=[worker])[worker]
                    os.kill(pid, signal.SIGKILL)
                    killed.append(pid)
                    return
            time.sleep(0.005)

    watcher = threading.Thread(target=kill_a_correcting_worker)
    watcher.start()
    results = posekit.distributed.correct_sequence(V_ref, frames, F, client=client, chunk_frames=2, device="cpu")
    watcher.join()
    assert killed, "no worker was seen correcting frames"
    expect_same(results, alone)


def test_a_pose_set_in_order(client, arm):
    V_ref, F = posekit.read_mesh(str(arm["rest"]))
    targets = [posekit.read_mesh(str(arm["bent"]))[0], posekit.read_mesh(str(arm["frames"][4]))[0]]
    results = posekit.distributed.correct(V_ref, targets, F, client=client, device="cpu")
    for (V, report), target in zip(results, targets):
        V_alone, _ = posekit.correct(V_ref, target, F, device="cpu")
        assert (V == V_alone).all()
        assert report["result"]["intersecting_faces"]["new"] == 0
