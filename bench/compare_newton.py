#!/usr/bin/env python3
"""Newton iterations and wall time of scenes under several solver settings, in one run.

    /usr/bin/python3 bench/compare_newton.py build/sinew [SCENE.json ...] [--repeat N]

Each scene runs with `solver.projection` "clamp" without and with the predictor, "adaptive" (the
default) and "none"; prints the Newton iterations per frame and in all, whether every frame
converged, and the median wall time of N runs (default 3). The machine is shared: compare the
ratios within one run. docs/scene-format.md (Solver) quotes its table.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

VARIANTS = [
    ("clamp, no predictor", {"projection": "clamp", "predictor": "none"}),
    ("clamp", {"projection": "clamp"}),
    ("adaptive (default)", {"projection": "adaptive"}),
    ("none", {"projection": "none"}),
]
DEFAULT_SCENES = ["examples/stretch_small.json", "examples/twist.json", "examples/verification/cook_membrane.json",
                  "examples/verification/thick_cylinder.json", "examples/drop_test.json"]


def absolute_paths(scene, path):
    base = os.path.dirname(os.path.abspath(path))
    mesh = scene.get("mesh", {})
    for key in ("file", "surface"):
        if isinstance(mesh.get(key), str):
            mesh[key] = os.path.join(base, mesh[key])
    if isinstance(scene.get("rig"), str):
        scene["rig"] = os.path.join(base, scene["rig"])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("sinew")
    parser.add_argument("scenes", nargs="*")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    scenes = args.scenes or DEFAULT_SCENES
    with tempfile.TemporaryDirectory() as tmp:
        for path in scenes:
            print(path)
            for name, settings in VARIANTS:
                scene = json.load(open(path))
                absolute_paths(scene, path)
                solver = scene.setdefault("solver", {})
                solver.update(settings)
                if "dynamics" in scene or "constraints" in scene:
                    solver.pop("predictor", None)  # quasistatic only
                file = os.path.join(tmp, "scene.json")
                json.dump(scene, open(file, "w"))
                out = os.path.join(tmp, "out")
                times = []
                for _ in range(args.repeat):
                    start = time.monotonic()
                    run = subprocess.run([args.sinew, "run", file, "--out", out, "--quiet"], capture_output=True,
                                         text=True)
                    times.append(time.monotonic() - start)
                if run.returncode not in (0, 3):
                    print(f"  {name:22s} exit {run.returncode}: {run.stderr.strip()[:200]}")
                    continue
                summary = json.load(open(os.path.join(out, "summary.json")))
                its = [f["newton_iterations"] for f in summary["frames"]]
                shown = its if len(its) <= 12 else its[:12] + ["..."]
                print(f"  {name:22s} Newton {sum(its):5d}  converged {all(f['converged'] for f in summary['frames'])!s:5s}"
                      f"  median {statistics.median(times):6.2f} s  per frame {shown}")
    print(f"machine: {os.cpu_count()} CPUs; {args.repeat} runs per variant")


if __name__ == "__main__":
    sys.exit(main())
