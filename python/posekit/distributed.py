"""posekit.distributed: pose sets and animations corrected on a Dask cluster.

    from dask.distributed import Client
    results = posekit.distributed.correct_sequence(V_ref, frames, F, client=Client("tcp://scheduler:8786"))

``client`` is a ``dask.distributed.Client``, a scheduler address, or None for a ``LocalCluster`` of
worker processes on this machine (closed again at the end). Every task carries the reference, the
faces and its frames, so that the scheduler can run it again on another worker. Results come back in order and are the same, bit for bit, as on one machine: a
sequence is corrected in two passes that follow ``posekit.correct_sequence`` exactly. First the runs
of consecutive frames that need a correction (a frame's correction may be carried to the next, so a
run is never split), grouped into tasks of about ``chunk_frames`` frames; then the blend in time, in
chunks that read ``posekit.blend_radius(smoothing)`` more frames on each side. A worker that dies
costs the scheduler a retry of its task; each frame comes back exactly once.
"""

import contextlib
import warnings
from typing import Callable, List, Optional, Sequence, Tuple

import numpy as np

from . import _posekit

__all__ = ["correct", "correct_sequence"]


@contextlib.contextmanager
def _connected(client):
    from dask.distributed import Client, LocalCluster

    with warnings.catch_warnings():
        # Each task carries its inputs (the reference, the faces, its frames) rather than futures of
        # scattered data: the scheduler can then run it again on another worker when its worker dies.
        # Scattered data can die with a worker; broadcast copies are made in the background, and a
        # worker killed before they were all made took the reference with it and cancelled the run.
        warnings.filterwarnings("ignore", message="Large object of size", category=UserWarning)
        with _client_of(client, Client, LocalCluster) as connected:
            yield connected


@contextlib.contextmanager
def _client_of(client, Client, LocalCluster):
    if client is None:
        with LocalCluster(processes=True, threads_per_worker=1) as cluster, Client(cluster) as local:
            yield local
    elif isinstance(client, str):
        with Client(client) as remote:
            yield remote
    else:
        yield client


def _new_faces(V_ref, frames, F):
    return [_posekit.check(V, F, reference=V_ref)["new_self_intersecting_faces"] for V in frames]


def _own_corrections(V_ref, frames, F, options):
    results, _ = _posekit.correct_sequence(V_ref, frames, F, smoothing=0.0, **options)
    return results


def _blended(V_ref, frames, earlier, F, smoothing, options, first, last):
    results, _ = _posekit.correct_sequence(V_ref, frames, F, smoothing=smoothing, earlier=earlier, **options)
    return results[first:last]


def _correct_one(V_ref, V, F, options):
    return _posekit.correct(V_ref, V, F, **options)


def _runs(needs: Sequence[int]) -> List[Tuple[int, int]]:
    """[first, last) of each run of consecutive frames that need a correction."""
    runs, start = [], None
    for t, count in enumerate(list(needs) + [0]):
        if count > 0 and start is None:
            start = t
        elif count == 0 and start is not None:
            runs.append((start, t))
            start = None
    return runs


def _tasks_of_runs(runs: List[Tuple[int, int]], chunk_frames: int) -> List[Tuple[int, int]]:
    """Consecutive runs grouped into spans of about chunk_frames frames; a run is never split."""
    spans = []
    for first, last in runs:
        if spans and last - spans[-1][0] <= chunk_frames:
            spans[-1] = (spans[-1][0], last)
        else:
            spans.append((first, last))
    return spans


def _check_sequence(V_ref, frames, F):
    V_ref = np.asarray(V_ref)
    frames = [np.asarray(V) for V in frames]
    if len(frames) == 0:
        raise ValueError("the sequence has no frame")
    for t, V in enumerate(frames):
        if V.shape != V_ref.shape:
            raise ValueError(f"frames[{t}] has shape {V.shape} but V_ref has {V_ref.shape}")
    return V_ref, frames


def correct_sequence(V_ref, frames: Sequence[np.ndarray], F, client=None, chunk_frames: int = 32,
                     smoothing: float = 2.0, carry: bool = True,
                     progress: Optional[Callable[[int, int], None]] = None, **options) -> List[tuple]:
    """Corrects every frame of an animation against V_ref on a Dask cluster, coherently in time.

    frames: float64 n x 3 arrays in time order; F: int m x 3, shared. chunk_frames: about how many
    frames one task corrects. smoothing, carry and the other keywords are those of
    posekit.correct_sequence (the command line's options). progress: called with (frames done,
    frames). Returns a (V, report) per frame, in order, as posekit.correct_sequence returns them.
    """
    if chunk_frames < 1:
        raise ValueError(f"chunk_frames must be >= 1, got {chunk_frames}")
    V_ref, frames = _check_sequence(V_ref, frames, F)
    count = len(frames)
    options = dict(options, carry=carry)
    with _connected(client) as dask:
        reference, faces = V_ref, np.asarray(F)
        spans = [(a, min(a + chunk_frames, count)) for a in range(0, count, chunk_frames)]
        needs = sum(dask.gather([dask.submit(_new_faces, reference, frames[a:b], faces, pure=False)
                                 for a, b in spans]), [])
        own: List[Optional[np.ndarray]] = [None] * count
        reports: List[Optional[dict]] = [None] * count
        done = count - sum(1 for n in needs if n > 0)
        if progress:
            progress(done, count)
        from dask.distributed import as_completed

        futures = {dask.submit(_own_corrections, reference, frames[a:b], faces, options, pure=False): (a, b)
                   for a, b in _tasks_of_runs(_runs(needs), chunk_frames)}
        for future in as_completed(futures):
            a, b = futures[future]
            for t, (V, report) in zip(range(a, b), future.result()):
                if needs[t] > 0:
                    own[t], reports[t] = V, report
            done += sum(1 for t in range(a, b) if needs[t] > 0)
            if progress:
                progress(done, count)
        radius = _posekit.blend_radius(smoothing)
        blends = []
        for a, b in spans:
            lo, hi = max(0, a - radius), min(count, b + radius)
            blends.append(dask.submit(_blended, reference, frames[lo:hi], own[lo:hi], faces, smoothing, options,
                                      a - lo, b - lo, pure=False))
        results = sum(dask.gather(blends), [])
    # The blend's reports say the frames' own corrections were reused; the first pass's say how they were made.
    out = []
    for t, (V, report) in enumerate(results):
        if reports[t] is not None:
            for key in ("reused", "carried", "carried_scale", "seconds", "error"):
                if key in reports[t]:
                    report[key] = reports[t][key]
            if "correction" in reports[t]:
                report["correction"] = reports[t]["correction"]
        report["name"] = f"frame {t}"
        out.append((V, report))
    return out


def correct(V_ref, targets: Sequence[np.ndarray], F, client=None,
            progress: Optional[Callable[[int, int], None]] = None, **options) -> List[tuple]:
    """Corrects each of targets (float64 n x 3 arrays) against V_ref on a Dask cluster, one task per
    target. The keywords are those of posekit.correct. Returns a (V, report) per target, in order."""
    V_ref, targets = _check_sequence(V_ref, targets, F)
    with _connected(client) as dask:
        reference, faces = V_ref, np.asarray(F)
        futures = [dask.submit(_correct_one, reference, V, faces, options, pure=False) for V in targets]
        if progress:
            from dask.distributed import as_completed

            progress(0, len(targets))
            for done, _ in enumerate(as_completed(futures), start=1):
                progress(done, len(targets))
        return dask.gather(futures)
