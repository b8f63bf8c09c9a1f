#!/usr/bin/env python3
"""Wall time per frame of a long `sinew run` of a tiny scene, early and late in the run.

A frame's own work does not change over the run here (a 2 x 1 x 1 hexahedral bar stretched by
1e-5 per frame: one or two Newton iterations), so any growth between the early and the late
figure is what the run's bookkeeping costs per frame as frames accumulate (summary.json,
checkpoint.json, simulation.pvd, frames.jsonl: docs/hardening.md, "Per-frame cost").

    bench/frame_cost.py [--sinew build/sinew] [--frames 2000] [--at 100 2000] [--window 50] [--repeat 1]

Prints, for each frame F in --at, the mean wall time and CPU time (user + system of the sinew
process, from /proc) of frames F-window+1..F, taken when each "frame N/M:" progress line arrives
on stderr, and the ratios late/early. On a machine shared with other work the wall time varies
with the load; the CPU time much less. With --repeat N, the medians of N runs.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SCENE = {
    "description": "bench/frame_cost.py: a tiny bar stretched a little every frame",
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]}, "cells": [2, 1, 1]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [
        {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
        {"name": "right", "select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}},
         "motion": {"type": "translate", "per_frame": [1e-5, 0, 0]}},
    ],
    "frames": 1,
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sinew", default=str(Path(__file__).resolve().parent.parent / "build" / "sinew"))
    ap.add_argument("--frames", type=int, default=2000)
    ap.add_argument("--at", type=int, nargs="+", default=[100, 2000])
    ap.add_argument("--window", type=int, default=50)
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    runs = [run_once(args) for _ in range(args.repeat)]
    wall = {f: statistics.median(r[0][f] for r in runs) for f in args.at}
    cpu = {f: statistics.median(r[1][f] for r in runs) for f in args.at}
    for f in args.at:
        print(f"frame {f}: {wall[f]:.2f} ms wall, {cpu[f]:.2f} ms CPU per frame (mean of frames "
              f"{f - args.window + 1}-{f}{', median of %d runs' % args.repeat if args.repeat > 1 else ''})")
    first, last = args.at[0], args.at[-1]
    print(f"ratio frame {last} / frame {first}: wall {wall[last] / wall[first]:.2f}, CPU {cpu[last] / cpu[first]:.2f}; "
          f"{args.frames} frames in {statistics.median(r[2] for r in runs):.1f} s")


def cpu_seconds(pid):
    """User + system CPU seconds of a running process (fields 14 and 15 of /proc/PID/stat)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def run_once(args):
    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / "bar.json"
        scene.write_text(json.dumps(SCENE))
        cmd = [args.sinew, "run", str(scene), "--out", str(Path(tmp) / "out"), "--frames", str(args.frames),
               "--threads", "1"]
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        done, cpu = {}, {}
        start = time.perf_counter()
        for line in proc.stderr:
            if line.startswith("frame ") and ":" in line.split()[1]:
                frame = int(line.split()[1].split("/")[0])
                done[frame] = time.perf_counter()
                cpu[frame] = cpu_seconds(proc.pid)
        if proc.wait() != 0:
            sys.exit(f"frame_cost: {' '.join(cmd)} exited {proc.returncode}")
        total = time.perf_counter() - start
    wall_ms, cpu_ms = {}, {}
    for f in args.at:
        lo = f - args.window
        if lo < 1 or f not in done or lo not in done:
            sys.exit(f"frame_cost: frame {f} (window {args.window}) is outside the run")
        wall_ms[f] = (done[f] - done[lo]) / args.window * 1e3
        cpu_ms[f] = (cpu[f] - cpu[lo]) / args.window * 1e3
    return wall_ms, cpu_ms, total


if __name__ == "__main__":
    main()
