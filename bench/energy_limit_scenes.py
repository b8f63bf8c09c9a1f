#!/usr/bin/python3
"""Paper 001's two example scenes through the CLI: median solver and wall milliseconds per frame.

    bench/energy_limit_scenes.py [--sinew build/sinew] [--old OTHER_BINARY] [--repeats 5]

Runs examples/falling_sphere.json and examples/beam_energy_limit.json `--repeats` times with
each binary, with the scene's output (VTU and OBJ per frame, plus frames.jsonl, checkpoint.json,
summary.json) and with `"output": {"vtu": false, "obj": false}`, and prints per scene and binary:

* solver ms/frame: median over frames and runs of the frames' `solve_seconds` in summary.json
  (the constrained stepper's own clock, summed over the frame's 5 substeps), and of `seconds`
  (the whole frame: the steps plus the frame's energies and measurements);
* wall ms/frame: the process's wall-clock time over the frame count (so it includes start-up and
  model building), median over runs, with and without the per-frame VTU/OBJ files;
* CPU ms/frame: the process's user + system CPU time over the frame count, median over runs (on a
  shared machine the wall clock also counts time the process waited for a core; CPU time does
  not).

Speed is measured here, never asserted in tests.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["falling_sphere", "beam_energy_limit"]


def scene_without_output(name, folder):
    path = os.path.join(ROOT, "examples", name + ".json")
    with open(path) as f:
        scene = json.load(f)
    if "file" in scene.get("mesh", {}):
        scene["mesh"]["file"] = os.path.join(ROOT, "examples", scene["mesh"]["file"])
    scene["output"] = {"vtu": False, "obj": False}
    out = os.path.join(folder, name + "_no_output.json")
    with open(out, "w") as f:
        json.dump(scene, f)
    return out


def run_once(binary, scene, out):
    start = time.perf_counter()
    proc = subprocess.Popen([binary, "run", scene, "--out", out], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"{binary} run {scene} failed")
    with open(os.path.join(out, "summary.json")) as f:
        frames = json.load(f)["frames"]
    return wall, usage.ru_utime + usage.ru_stime, frames


def measure(binaries, name, scene, repeats, folder):
    """Runs each binary `repeats` times, alternating between them so that they share the load."""
    runs = {label: ([], [], [], []) for label, _ in binaries}
    for r in range(repeats):
        for label, binary in binaries:
            w, c, frames = run_once(binary, scene, os.path.join(folder, f"{name}_{label}_{r}"))
            solve, frame, wall, cpu = runs[label]
            solve += [1e3 * f["solve_seconds"] for f in frames]
            frame += [1e3 * f["seconds"] for f in frames]
            wall.append(1e3 * w / len(frames))
            cpu.append(1e3 * c / len(frames))
    return {label: tuple(statistics.median(v) for v in runs[label]) for label, _ in binaries}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sinew", default=os.path.join(ROOT, "build", "sinew"))
    parser.add_argument("--old", help="a second binary to compare with (the two run alternately)")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    binaries = [("old", args.old)] if args.old else []
    binaries.append(("new" if args.old else "sinew", args.sinew))
    print(f"{'scene':<18} {'binary':<6} {'output':<7} {'solve ms/fr':>11} {'frame ms/fr':>11} {'wall ms/fr':>10} "
          f"{'CPU ms/fr':>9}")
    with tempfile.TemporaryDirectory(prefix="sinew_el_scenes_") as folder:
        for name in SCENES:
            scenes = [("files", os.path.join(ROOT, "examples", name + ".json")),
                      ("none", scene_without_output(name, folder))]
            for output, scene in scenes:
                results = measure(binaries, f"{name}_{output}", scene, args.repeats, folder)
                for label, _ in binaries:
                    s, f, w, c = results[label]
                    print(f"{name:<18} {label:<6} {output:<7} {s:>11.2f} {f:>11.2f} {w:>10.1f} {c:>9.1f}", flush=True)


if __name__ == "__main__":
    main()
