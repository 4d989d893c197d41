#!/usr/bin/env python3
"""Prints the quality and time table of posekit_interpolate_bench's JSON output (standard library only).

    posekit_interpolate_bench --benchmark_repetitions=5 --benchmark_format=json > interpolate.json
    python3 tools/bench/interpolation_table.py interpolate.json

One row per pose set and weight: for each method the 99th-percentile relative edge-length error (%),
the 99th-percentile dihedral-angle error (degrees) and the time of one weight (ms, the minimum over
the repetitions, or the single run), then MixIT's errors over the edge method's.
"""
import json
import sys

METHODS = ("mixit", "edge", "vertex")


def milliseconds(value):
    return f"{value:.1f}" if value >= 1.0 else f"{value:.2g}"


def main(path):
    with open(path) as stream:
        report = json.load(stream)
    rows = {}
    for run in report["benchmarks"]:
        name = run["name"]
        if not name.startswith("interpolate/") or run.get("error_occurred"):
            continue
        parts = run.get("run_name", name).split("/")
        key = (parts[1], parts[3])
        method = parts[2]
        entry = rows.setdefault(key, {}).setdefault(method, {})
        aggregate = run.get("aggregate_name", "")
        if aggregate in ("", "min"):
            # A single run, or the minimum of the repetitions, gives the time; counters do not vary.
            if aggregate == "min" or "time" not in entry:
                entry["time"] = run["real_time"]
            entry["len"] = run["len_p99_pct"]
            entry["dih"] = run["dih_p99_deg"]
    header = ["pose set", "weight"]
    for method in METHODS:
        header += [method + " len p99 %", method + " dih p99 deg", method + " ms"]
    header += ["mixit/edge len", "mixit/edge dih"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for (pose_set, weight), methods in rows.items():
        cells = [pose_set, weight]
        for method in METHODS:
            m = methods.get(method)
            cells += ["-", "-", "-"] if m is None else [f"{m['len']:.2f}", f"{m['dih']:.2f}", milliseconds(m["time"])]
        mixit, edge = methods.get("mixit"), methods.get("edge")
        if mixit and edge and edge["len"] > 0 and edge["dih"] > 0:
            cells += [f"{mixit['len'] / edge['len']:.2f}", f"{mixit['dih'] / edge['dih']:.2f}"]
        else:
            cells += ["-", "-"]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "interpolate.json")
