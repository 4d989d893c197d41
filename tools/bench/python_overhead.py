#!/usr/bin/env python3
"""The Python package's calling overhead: posekit.correct on a pose pair against the command line's
`posekit correct` on the same files, each run REPEAT times; prints the minimum and the median of each
and their ratio. The command line's time includes reading the two meshes and writing the result, so
the Python call is timed the same way (read_mesh twice, correct, write_mesh).

  PYTHONPATH=build/release/python python3 tools/bench/python_overhead.py build/release/tools/cli/posekit \\
      ../shared/data/lion-poses/lion-reference.obj ../shared/data/lion-poses/lion-01.obj
"""

import statistics
import subprocess
import sys
import tempfile
import time

import posekit


def main() -> int:
    if len(sys.argv) < 4:
        print(__doc__, file=sys.stderr)
        return 2
    cli, reference, target = sys.argv[1:4]
    repeat = int(sys.argv[4]) if len(sys.argv) > 4 else 5
    with tempfile.TemporaryDirectory() as folder:
        cli_times, python_times = [], []
        for _ in range(repeat):
            start = time.perf_counter()
            subprocess.run([cli, "correct", reference, target, "-o", f"{folder}/cli.obj", "--device", "cpu"],
                           check=True, capture_output=True)
            cli_times.append(time.perf_counter() - start)
            start = time.perf_counter()
            V_ref, F = posekit.read_mesh(reference)
            V, _ = posekit.read_mesh(target)
            V_out, _ = posekit.correct(V_ref, V, F, device="cpu")
            posekit.write_mesh(f"{folder}/python.obj", V_out, F)
            python_times.append(time.perf_counter() - start)
        same = (posekit.read_mesh(f"{folder}/cli.obj")[0] == posekit.read_mesh(f"{folder}/python.obj")[0]).all()
    for name, times in (("command line", cli_times), ("python", python_times)):
        print(f"{name:13s} min {min(times):.3f} s  median {statistics.median(times):.3f} s")
    print(f"python / command line: min {min(python_times) / min(cli_times):.3f}, "
          f"median {statistics.median(python_times) / statistics.median(cli_times):.3f}; same vertices: {bool(same)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
