#!/usr/bin/python3
"""Stress-stretch curves of material families normalised to the same E and nu.

Runs `build/sinew material curve --csv` (uniaxial tension/compression, lateral faces free) for
several families at the same Young's modulus and Poisson's ratio (paper 002 §4), and for the
Stable Neo-Hookean material at several nonlinearity exponents alpha (paper 002 §5, Fig. 3),
and writes docs/img/stress_stretch.png. Families missing from the catalog are skipped with a
note; a curve that stops existing (no lateral stretch frees the lateral faces, e.g. StVK's
volume term under strong tension) is drawn up to where it exists, with a note.

Usage: scripts/plot_material_curves.py [--sinew build/sinew] [--out docs/img/stress_stretch.png]
                                       [--E 1e5] [--nu 0.45]
"""
import argparse
import csv
import io
import json
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

FAMILIES = ["linear_corotational", "stvk", "neo_hookean", "stable_neo_hookean", "hencky",
            "mooney_rivlin", "valanis_landel", "arruda_boyce", "fung"]
# Mixes (paper 002 §6), (lambda family, mu family): corotational and StVK shear with the
# Neo-Hookean volume term (J - 1)^2; the latter keeps StVK's curve alive under strong tension.
MIXES = [("neo_hookean_ogden", "linear_corotational"), ("neo_hookean_ogden", "stvk")]
ALPHA_FAMILY = "stable_neo_hookean"
ALPHAS = [0.5, 1.0, 2.0, 3.0]


def note(text):
    print(f"plot_material_curves: {text}", file=sys.stderr)


def run_sinew(sinew, args):
    return subprocess.run([str(sinew), *args], capture_output=True, text=True)


def curve(sinew, material_args, lo, hi, steps):
    """(stretch, stress) columns; shrinks the range where the curve stops existing."""
    err = "range kept shrinking"
    for _ in range(8):
        r = run_sinew(sinew, ["material", "curve", *material_args, "--stretch-from", repr(lo),
                              "--stretch-to", repr(hi), "--steps", str(steps), "--csv"])
        if r.returncode == 0:
            rows = list(csv.DictReader(io.StringIO(r.stdout)))
            return [float(x["stretch"]) for x in rows], [float(x["stress"]) for x in rows], None
        err = r.stderr.strip()
        m = re.search(r"(uniaxial|biaxial) stretch ([-+0-9.eE]+):", r.stderr)
        if not m:
            return None, None, r.stderr.strip()
        bad, h = float(m.group(2)), (hi - lo) / steps
        if bad >= 1.0:
            hi = bad - h
        else:
            lo = bad + h
        if not lo < 1.0 < hi:
            return None, None, err
    return None, None, err


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sinew", default=str(ROOT / "build" / "sinew"))
    ap.add_argument("--out", default=str(ROOT / "docs" / "img" / "stress_stretch.png"))
    ap.add_argument("--E", type=float, default=1e5)
    ap.add_argument("--nu", type=float, default=0.45)
    ap.add_argument("--from", dest="lo", type=float, default=0.5)
    ap.add_argument("--to", dest="hi", type=float, default=2.5)
    ap.add_argument("--steps", type=int, default=80)
    a = ap.parse_args()

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        note("matplotlib is not installed (Debian: python3-matplotlib)")
        return 1
    sinew = pathlib.Path(a.sinew)
    if not sinew.exists():
        note(f"{sinew} not found; build first (scripts/setup)")
        return 1
    listing = run_sinew(sinew, ["materials", "--json"])
    if listing.returncode != 0:
        note(listing.stderr.strip())
        return 1
    families = json.loads(listing.stdout)["families"]
    known = {f["name"] for f in families}
    not_rest_stable = {f["name"] for f in families if not f["rest_stable"]}
    target = ["--E", repr(a.E), "--nu", repr(a.nu)]

    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5.2))
    for name in FAMILIES:
        if name not in known:
            note(f"skipping {name}: not in this build's catalog")
            continue
        if name in not_rest_stable:  # stressed at rest: no free lateral state near s = 1
            note(f"skipping {name}: not rest-stable")
            continue
        s, p, err = curve(sinew, ["--material", name, *target], a.lo, a.hi, a.steps)
        if s is None:
            note(f"skipping {name}: {err}")
            continue
        if s[0] > a.lo + 1e-12 or s[-1] < a.hi - 1e-12:
            note(f"{name}: curve exists only for stretch in [{s[0]:.3g}, {s[-1]:.3g}]")
        left.plot(s, [x / a.E for x in p], label=name)
    for lam, mu in MIXES:
        if lam not in known or mu not in known:
            note(f"skipping mix {lam} + {mu}: not in this build's catalog")
            continue
        s, p, err = curve(sinew, ["--mix-lambda", lam, "--mix-mu", mu, *target], a.lo, a.hi,
                          a.steps)
        if s is None:
            note(f"skipping mix {lam} + {mu}: {err}")
            continue
        left.plot(s, [x / a.E for x in p], "--", label=f"mix: {mu} + volume of {lam}")
    left.set_title(f"Uniaxial, all normalised to E = {a.E:g}, nu = {a.nu:g}")

    if ALPHA_FAMILY in known:
        for alpha in ALPHAS:
            s, p, err = curve(sinew, ["--material", ALPHA_FAMILY, *target, "--alpha", repr(alpha)],
                              a.lo, a.hi, a.steps)
            if s is None:
                note(f"skipping {ALPHA_FAMILY} alpha = {alpha}: {err}")
                continue
            right.plot(s, [x / a.E for x in p], label=f"alpha = {alpha:g}")
        right.set_title(f"{ALPHA_FAMILY}, nonlinearity exponent alpha (paper 002 Eq. 16)")
    else:
        note(f"skipping the alpha panel: {ALPHA_FAMILY} not in this build's catalog")
        right.set_title(f"{ALPHA_FAMILY} not available")

    for ax in (left, right):
        ax.axhline(0.0, color="0.7", lw=0.8)
        ax.axvline(1.0, color="0.7", lw=0.8)
        ax.plot([a.lo, a.hi], [a.lo - 1.0, a.hi - 1.0], ":", color="0.4", lw=1.0,
                label="E (s - 1), the common linearisation")
        ax.set_xlabel("stretch s")
        ax.set_ylabel("nominal stress P00 / E")
        ax.set_ylim(-1.5, 3.0)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    out = pathlib.Path(a.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
