"""A stretch test driven frame by frame: a bar pinned at its left end, its right end moved by
this script before every frame (sinew.Simulation.move_boundary). After each frame it reads the
reaction force, volume, smallest J and largest von Mises stress, compares the force with the
material's uniaxial curve times the cross-section, and writes a plot (and, with --frames-dir,
the frames for ParaView).

    PYTHONPATH=build/python python3 examples/python/stretch_frame_by_frame.py --out stretch.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import sinew

LENGTH, SIDE = 4.0, 1.0

SCENE = {
    "description": "A bar stretched by a Python script",
    "mesh": {"box": {"min": [0, 0, 0], "max": [LENGTH, SIDE, SIDE]}, "cells": [12, 3, 3]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45},
    "boundary": [
        {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
        {"name": "right", "select": {"plane": {"point": [LENGTH, 0, 0], "normal": [1, 0, 0]}}},
    ],
    "solver": {"newton": {"residual_tolerance": 1e-8}},
}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="stretch.png", help="the PNG to write")
    parser.add_argument("--frames-dir", help="also write the frames (VTU, OBJ, summary.json) here")
    parser.add_argument("--steps", type=int, default=6)
    parser.add_argument("--max-stretch", type=float, default=2.0)
    args = parser.parse_args()

    sim = sinew.Simulation(sinew.Scene.from_dict(SCENE), out=args.frames_dir)
    stretches, forces, min_J, von_mises = [1.0], [0.0], [1.0], [0.0]
    print(f"{'frame':>5}{'stretch':>9}{'force':>12}{'volume':>9}{'min J':>8}{'von Mises':>11}{'Newton':>7}")
    for k in range(1, args.steps + 1):
        stretch = 1.0 + (args.max_stretch - 1.0) * k / args.steps
        sim.move_boundary("right", translation=[(stretch - 1.0) * LENGTH, 0.0, 0.0])
        record = sim.step()
        if not record.converged:
            raise SystemExit(f"frame {record.frame} did not converge: {record.failure}")
        force = record.reactions[sim.boundary_names.index("right"), 0]
        vm = sinew.von_mises(sim.stresses()["cauchy"]).max()
        stretches.append(stretch)
        forces.append(force)
        min_J.append(record.min_J)
        von_mises.append(vm)
        print(f"{record.frame:>5}{stretch:>9.3f}{force:>12.5g}{record.volume:>9.4f}{record.min_J:>8.3f}"
              f"{vm:>11.4g}{record.newton_iterations:>7}")
    assert np.all(np.diff(forces) > 0), "the force should grow with the stretch"

    # The same material in a homogeneous uniaxial test, times the rest cross-section: the bar's
    # clamped ends make it a little stiffer.
    curve = sim.material.curve("uniaxial", 1.0, args.max_stretch, 40)
    fig, (f_ax, j_ax) = plt.subplots(1, 2, figsize=(10, 4))
    f_ax.plot(stretches, forces, "o-", label="bar, clamped ends (Sinew)")
    f_ax.plot(curve["stretch"], curve["stress"] * SIDE * SIDE, "k--", label="homogeneous uniaxial")
    f_ax.set(xlabel="stretch", ylabel="force on the right end", title="stretch test, frame by frame")
    f_ax.legend()
    j_ax.plot(stretches, min_J, "o-", label="min J")
    j_ax.set(xlabel="stretch", ylabel="min J", title="volume change")
    vm_ax = j_ax.twinx()
    vm_ax.plot(stretches, von_mises, "s-", color="tab:red", label="max von Mises")
    vm_ax.set_ylabel("max von Mises stress", color="tab:red")
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
