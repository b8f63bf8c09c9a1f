#!/usr/bin/python3
"""Plots of a Sinew run folder (what `sinew plot OUT_DIR` runs; docs/plots.md).

Reads OUT_DIR/summary.json and writes PNG and SVG files into the plot folder:
  convergence     iterations per frame and the residual they ended at; when frames carry a
                  per-iteration residual history ("residuals"), one curve per frame
  reactions       force each boundary condition exerts on the body, per frame (quasistatic runs)
  volume          volume / rest volume and smallest element J per frame
  energy          elastic, kinetic, potential and total energy over time (or frame)
  stress_stretch  uniaxial stress-stretch curve of the scene's material (`sinew material curve`)
A plot whose data the summary does not hold is skipped with a note on stderr.

Every problem with the input (missing folder, no summary.json, malformed JSON, a field of the
wrong shape) is one line on stderr naming the file and the reason, and exit code 2.

Usage: sinew_plot.py OUT_DIR [--plots DIR] [--format png,svg] [--sinew PATH] [--only NAMES]
"""
import argparse
import json
import math
import os
import pathlib
import subprocess
import sys


class PlotError(Exception):
    """An input problem: `where` (file, or file: field) and the reason."""

    def __init__(self, where, reason):
        super().__init__(f"{where}: {reason}")


def note(text):
    print(f"sinew plot: {text}", file=sys.stderr)


# ---- summary.json -------------------------------------------------------------------------
# Everything the plots know about summary.json is in read_summary: it turns the runner's file
# into the plain record below, so a change of the file's schema is adapted here only.

class Run:
    """What the plots use of a run, one list entry per completed frame."""

    def __init__(self):
        self.scene = None            # scene file as the runner named it (may be relative)
        self.material_spec = None    # the scene's /material object, when known
        self.material = ""           # material name for titles
        self.rest_volume = None
        self.frames = []             # frame numbers
        self.times = None            # seconds per frame (dynamic runs), else None
        self.converged = []
        self.counters = {}           # name -> per-frame counts (Newton, linear, SQP, PGS ...)
        self.residual = []           # per frame: the residual (or constraint error) it ended at
        self.residual_name = "residual"
        self.residual_history = None  # per frame: list of residuals per iteration, or None
        self.volume = []
        self.min_J = None            # per frame, or None when the runner did not record it
        self.reactions = {}          # boundary name -> per-frame [fx, fy, fz]
        self.energies = {}           # name -> per-frame energy
        self.dynamic = False


def _field(record, key, where, kind=float, optional=False):
    if key not in record:
        if optional:
            return None
        raise PlotError(where, f"missing \"{key}\"")
    value = record[key]
    try:
        if kind is float:
            if isinstance(value, bool) or value is None:
                raise TypeError
            value = float(value)
        elif kind is int:
            if isinstance(value, bool) or not isinstance(value, int):
                raise TypeError
        elif kind is bool:
            if not isinstance(value, bool):
                raise TypeError
    except (TypeError, ValueError):
        raise PlotError(where, f"\"{key}\" must be {kind.__name__}, got {json.dumps(value)[:40]}") from None
    return value


def read_summary(path):
    """Reads a run's summary.json into a Run; PlotError naming the file (and field) if bad."""
    path = pathlib.Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise PlotError(path, "no summary.json (is this a `sinew run` output folder?)") from None
    except OSError as e:
        raise PlotError(path, f"cannot read: {e.strerror}") from None
    try:
        s = json.loads(text)
    except json.JSONDecodeError as e:
        raise PlotError(f"{path}:{e.lineno}", f"malformed JSON: {e.msg}") from None
    if not isinstance(s, dict):
        raise PlotError(path, "expected a JSON object at the top")
    frames = s.get("frames")
    if not isinstance(frames, list):
        raise PlotError(path, "\"frames\" must be a list of frame records")
    if not frames:
        raise PlotError(path, "no completed frame to plot (\"frames\" is empty)")

    run = Run()
    run.scene = s.get("scene")
    run.material_spec = s.get("material_spec")
    run.material = str(s.get("material", ""))
    run.rest_volume = _field(s, "rest_volume", f"{path}: /rest_volume", optional=True)
    integrator = s.get("integrator")

    def counter(f, key, where, kind=float):
        """A frame's count or measure: top level (older summaries) or under "counters"."""
        if key in f:
            return _field(f, key, where, kind)
        counters = f.get("counters")
        if not isinstance(counters, dict) or key not in counters:
            raise PlotError(where, f"missing \"{key}\"")
        return _field(counters, key, f"{where}/counters", kind)

    first = frames[0] if isinstance(frames[0], dict) else {}
    constrained = integrator == "energy_limited" or "sqp_iterations" in first or \
        "sqp_iterations" in (first.get("counters") or {})
    boundary = s.get("boundary", [])
    if not isinstance(boundary, list):
        raise PlotError(f"{path}: /boundary", "must be a list of names")
    names = [str(b) if b else f"boundary {i}" for i, b in enumerate(boundary)]
    counter_keys = ({"SQP iterations": "sqp_iterations", "PGS iterations": "pgs_iterations"} if constrained
                    else {"Newton iterations": "newton_iterations", "linear iterations": "linear_iterations"})
    for name in counter_keys:
        run.counters[name] = []
    histories, times = [], []
    for i, f in enumerate(frames):
        where = f"{path}: /frames/{i}"
        if not isinstance(f, dict):
            raise PlotError(where, "must be an object")
        run.frames.append(_field(f, "frame", where, int))
        run.converged.append(_field(f, "converged", where, bool))
        for name, key in counter_keys.items():
            run.counters[name].append(int(counter(f, key, where)))
        run.volume.append(_field(f, "volume", where))
        t = _field(f, "time", where, optional=True)
        if t is not None:
            times.append(t)
        min_j = _field(f, "min_J", where, optional=True)
        if min_j is not None:
            run.min_J = (run.min_J or []) + [min_j]
        if constrained:
            run.residual_name = "constraint error (energy violation, penetration)"
            run.residual.append(max(counter(f, "max_energy_violation", where), counter(f, "max_penetration", where)))
        else:
            run.residual.append(_field(f, "residual", where))
        # Elastic plus load and contact potential; older summaries have "elastic_energy" (constrained
        # runs) or only "energy".
        potential = _field(f, "potential_energy", where, optional=True)
        if potential is not None:
            run.energies.setdefault("potential (elastic, loads, contact)", []).append(potential)
        elif "elastic_energy" in f:
            run.energies.setdefault("elastic", []).append(_field(f, "elastic_energy", where))
        else:
            run.energies.setdefault("potential (elastic, loads, contact)", []).append(_field(f, "energy", where))
        run.energies.setdefault("kinetic", []).append(_field(f, "kinetic_energy", where, optional=True) or 0.0)
        reactions = f.get("reactions", [])
        if not isinstance(reactions, list):
            raise PlotError(f"{where}/reactions", "must be a list of [fx, fy, fz]")
        for b, r in enumerate(reactions):
            if not (isinstance(r, list) and len(r) == 3 and all(isinstance(c, (int, float)) for c in r)):
                raise PlotError(f"{where}/reactions/{b}", "must be [fx, fy, fz]")
            name = names[b] if b < len(names) else f"boundary {b}"
            run.reactions.setdefault(name, []).append([float(c) for c in r])
        # Per-iteration history: "residuals": [r_1, r_2, ...] (Newton iterations, or SQP steps).
        h = f.get("residuals")
        if h is not None:
            if not (isinstance(h, list) and all(isinstance(r, (int, float)) for r in h)):
                raise PlotError(f"{where}/residuals", "must be a list of numbers")
            histories.append([float(r) for r in h])
    if histories and len(histories) == len(frames):
        run.residual_history = histories
    if integrator is not None:
        run.dynamic = integrator != "quasistatic"
    else:
        run.dynamic = constrained or any(k != 0.0 for k in run.energies.get("kinetic", []))
    if not run.dynamic:
        run.energies.pop("kinetic", None)
    if run.dynamic and len(times) == len(frames):
        run.times = times
    for name, rows in list(run.reactions.items()):
        if len(rows) != len(run.frames):  # a boundary without a reaction in some frame
            del run.reactions[name]
    return run


# ---- plots --------------------------------------------------------------------------------

def frame_axis(run):
    if run.times is not None and len(run.times) == len(run.frames):
        return run.times, "time [s]"
    return run.frames, "frame"


def label_x(ax, xlabel):
    ax.set_xlabel(xlabel)
    if xlabel == "frame":
        from matplotlib.ticker import MaxNLocator
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))


def mark_unconverged(ax, run, xs):
    bad = [x for x, ok in zip(xs, run.converged) if not ok]
    for x in bad:
        ax.axvline(x, color="red", linestyle=":", linewidth=1)
    if bad:
        ax.plot([], [], color="red", linestyle=":", label="not converged")


def plot_convergence(plt, run):
    xs, xlabel = frame_axis(run)
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 4))
    if run.residual_history:
        cmap = plt.get_cmap("viridis")
        n = len(run.residual_history)
        for k, (frame, h) in enumerate(zip(run.frames, run.residual_history)):
            ax0.semilogy(range(1, len(h) + 1), [max(r, 1e-300) for r in h], marker=".",
                         color=cmap(k / max(n - 1, 1)), label=f"frame {frame}" if n <= 10 else None)
        ax0.set_xlabel("iteration")
        ax0.set_ylabel("residual")
        ax0.set_title("residual per iteration")
        if n <= 10:
            ax0.legend(fontsize="small")
    else:
        positive = [(x, r) for x, r in zip(xs, run.residual) if r > 0]
        if positive:
            ax0.semilogy(*zip(*positive), marker="o")
        label_x(ax0, xlabel)
        ax0.set_ylabel(run.residual_name)
        ax0.set_title("final residual per frame")
        mark_unconverged(ax0, run, xs)
    for name, counts in run.counters.items():
        ax1.plot(xs, counts, marker="o", label=name)
    label_x(ax1, xlabel)
    ax1.set_ylabel("iterations per frame")
    ax1.set_title("solver iterations")
    ax1.legend()
    return fig


def translations(scene):
    """Boundary name -> per-frame displacement vector of the scene's translate motions."""
    out = {}
    boundary = scene.get("boundary", []) if isinstance(scene, dict) else []
    for i, b in enumerate(boundary if isinstance(boundary, list) else []):
        motion = b.get("motion") if isinstance(b, dict) else None
        if isinstance(motion, dict) and motion.get("type") == "translate":
            step = motion.get("per_frame")
            if isinstance(step, list) and len(step) == 3 and all(isinstance(c, (int, float)) for c in step):
                out[b.get("name") or f"boundary {i}"] = [float(c) for c in step]
    return out


def plot_reactions(plt, run, scene):
    if not run.reactions:
        return None
    xs, xlabel = frame_axis(run)
    moves = translations(scene) if not run.dynamic else {}
    fig, axes = plt.subplots(1, len(run.reactions), figsize=(5 * len(run.reactions), 4), squeeze=False)
    for ax, (name, rows) in zip(axes[0], run.reactions.items()):
        step = moves.get(name)
        length = math.sqrt(sum(c * c for c in step)) if step else 0.0
        if length > 0.0:  # a translated boundary: force against its displacement
            x, axis_label = [f * length for f in run.frames], f"displacement of \"{name}\" [m]"
        else:
            x, axis_label = xs, xlabel
        for c, label in enumerate("xyz"):
            ax.plot(x, [r[c] for r in rows], marker=".", label=f"$f_{label}$")
        ax.plot(x, [math.sqrt(sum(v * v for v in r)) for r in rows], color="black", linestyle="--", label="|f|")
        ax.axhline(0.0, color="grey", linewidth=0.5)
        label_x(ax, axis_label)
        ax.set_ylabel("force on the body [N]")
        ax.set_title(f"reaction of \"{name}\"")
        ax.legend(fontsize="small")
    return fig


def plot_volume(plt, run):
    xs, xlabel = frame_axis(run)
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 4))
    if run.rest_volume:
        ax0.plot(xs, [v / run.rest_volume for v in run.volume], marker="o")
        ax0.set_ylabel("volume / rest volume")
    else:
        ax0.plot(xs, run.volume, marker="o")
        ax0.set_ylabel("volume [m$^3$]")
    label_x(ax0, xlabel)
    ax0.set_title("volume")
    if run.min_J is not None and len(run.min_J) == len(xs):
        ax1.plot(xs, run.min_J, marker="o", color="tab:orange")
        ax1.axhline(0.0, color="red", linewidth=0.8)
        ax1.set_ylabel("smallest element J")
        ax1.set_title("min J (J <= 0: inverted element)")
    else:
        ax1.text(0.5, 0.5, "min J not recorded by this run", ha="center", va="center", transform=ax1.transAxes)
        ax1.set_axis_off()
    label_x(ax1, xlabel)
    return fig


def plot_energy(plt, run):
    if not run.energies:
        return None
    xs, xlabel = frame_axis(run)
    fig, ax = plt.subplots(figsize=(7, 4))
    for name, values in run.energies.items():
        ax.plot(xs, values, marker=".", label=name)
    if run.dynamic and len(run.energies) > 1:
        total = [sum(v) for v in zip(*run.energies.values())]
        ax.plot(xs, total, color="black", linestyle="--", label="total")
    label_x(ax, xlabel)
    ax.set_ylabel("energy [J]")
    ax.set_title("energy" + (" over time" if run.dynamic else " per frame"))
    ax.legend(fontsize="small")
    return fig


def load_scene(run, out_dir):
    """The scene file the summary names, as JSON (looked up as written, then beside OUT_DIR's
    parent), or (None, why not)."""
    if not run.scene:
        return None, "the summary names no scene file"
    candidates = [pathlib.Path(run.scene)]
    if not candidates[0].is_absolute():
        candidates.append(out_dir.parent / run.scene)
    for p in candidates:
        if p.is_file():
            try:
                scene = json.loads(p.read_text(encoding="utf-8"))
            except (OSError, json.JSONDecodeError) as e:
                return None, f"cannot read {p}: {e}"
            return (scene, None) if isinstance(scene, dict) else (None, f"{p} is not a scene object")
    return None, f"scene file {run.scene} not found (run `sinew plot` from where the scene was run)"


def material_spec(run, scene, why):
    """The scene's /material object: from the summary, else from the scene file."""
    if isinstance(run.material_spec, dict):
        return run.material_spec, None
    if scene is None:
        return None, why
    spec = scene.get("material")
    return (spec, None) if isinstance(spec, dict) else (None, f"{run.scene} has no /material object")


def plot_stress_stretch(plt, run, scene, scene_why, sinew):
    spec, why = material_spec(run, scene, scene_why)
    if spec is None:
        note(f"stress_stretch skipped: {why}")
        return None
    if not sinew:
        note("stress_stretch skipped: no sinew executable given (--sinew)")
        return None
    fig, ax = plt.subplots(figsize=(6, 4))
    for mode, lo, hi in (("uniaxial", 0.5, 2.0), ("biaxial", 0.7, 1.5)):
        r = subprocess.run([sinew, "material", "curve", "--material-json", json.dumps(spec), "--mode", mode,
                            "--stretch-from", str(lo), "--stretch-to", str(hi), "--steps", "60", "--json"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            note(f"stress_stretch: {mode} curve failed: {r.stderr.strip()}")
            continue
        points = json.loads(r.stdout)["points"]
        ax.plot([p["stretch"] for p in points], [p["stress"] for p in points], label=mode)
    if not ax.lines:
        plt.close(fig)
        return None
    ax.axhline(0.0, color="grey", linewidth=0.5)
    ax.axvline(1.0, color="grey", linewidth=0.5)
    ax.set_xlabel("stretch")
    ax.set_ylabel("nominal stress $P_{00}$ [Pa]")
    ax.set_title(f"{run.material or spec.get('family', 'material')}: stress-stretch")
    ax.legend()
    return fig


PLOTS = ["convergence", "reactions", "volume", "energy", "stress_stretch"]


def main(argv):
    parser = argparse.ArgumentParser(prog="sinew plot", description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", help="a `sinew run` output folder (holds summary.json)")
    parser.add_argument("--plots", help="where to write the plots (default OUT_DIR/plots)")
    parser.add_argument("--format", default="png,svg", help="comma-separated: png, svg (default both)")
    parser.add_argument("--only", help=f"comma-separated subset of {','.join(PLOTS)}")
    parser.add_argument("--sinew", help="sinew executable for the material curve")
    args = parser.parse_args(argv)

    out_dir = pathlib.Path(args.out_dir)
    formats = [f.strip() for f in args.format.split(",") if f.strip()]
    for f in formats:
        if f not in ("png", "svg"):
            raise PlotError("--format", f"unknown format '{f}' (png, svg)")
    if not formats:
        raise PlotError("--format", "names no format")
    only = PLOTS
    if args.only:
        only = [p.strip() for p in args.only.split(",") if p.strip()]
        for p in only:
            if p not in PLOTS:
                raise PlotError("--only", f"unknown plot '{p}' ({', '.join(PLOTS)})")
    if not out_dir.exists():
        raise PlotError(out_dir, "no such output folder")
    if not out_dir.is_dir():
        raise PlotError(out_dir, "not a folder (give the folder `sinew run --out` wrote)")
    run = read_summary(out_dir / "summary.json")

    try:
        import matplotlib
    except ImportError:
        raise PlotError("matplotlib", "not installed for this Python (Debian: apt-get install python3-matplotlib)") from None
    matplotlib.use("Agg")
    matplotlib.rcParams["svg.hashsalt"] = "sinew"  # same SVG for the same data
    import matplotlib.pyplot as plt

    plots_dir = pathlib.Path(args.plots) if args.plots else out_dir / "plots"
    try:
        plots_dir.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise PlotError(plots_dir, f"cannot create the plot folder: {e.strerror}") from None
    scene, scene_why = load_scene(run, out_dir)
    makers = {"convergence": lambda: plot_convergence(plt, run), "reactions": lambda: plot_reactions(plt, run, scene),
              "volume": lambda: plot_volume(plt, run), "energy": lambda: plot_energy(plt, run),
              "stress_stretch": lambda: plot_stress_stretch(plt, run, scene, scene_why, args.sinew)}
    written = []
    for name in only:
        fig = makers[name]()
        if fig is None:
            if name != "stress_stretch":
                note(f"{name} skipped: the summary holds no data for it")
            continue
        fig.tight_layout()
        for fmt in formats:
            target = plots_dir / f"{name}.{fmt}"
            tmp = plots_dir / f".{name}.{fmt}.tmp"
            try:  # whole file or none: written aside, then renamed
                fig.savefig(tmp, format=fmt, dpi=120, metadata={"Date": None} if fmt == "svg" else None)
                os.replace(tmp, target)
            except OSError as e:
                tmp.unlink(missing_ok=True)
                raise PlotError(target, f"cannot write: {e.strerror}") from None
            written.append(target)
        plt.close(fig)
    for p in written:
        print(p)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except PlotError as e:
        print(f"sinew: error: {e}", file=sys.stderr)
        sys.exit(2)
