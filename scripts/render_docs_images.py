#!/usr/bin/env python3
"""Regenerates every picture in docs/img with Sinew's own tooling:

- example_NAME.png (every examples/*.json), feature_NAME.png (every examples/features/*.json,
  shown under its scene in docs/scene-format.md) and viewer_page.png: each scene is run (small,
  a coarser mesh and/or fewer frames, where the example is large: see EXAMPLES), `sinew viewer`
  writes its browser viewer, and the viewer's headless screenshot (tests/browser/screenshot.mjs:
  Debian's chromium through playwright-core) is the picture;
- plot_*.png (docs/plots.md) by `sinew plot` (scripts/make_plot_examples.sh) and
  stress_stretch.png (docs/materials.md) by scripts/plot_material_curves.py.

Needs a build and the browser test tools (scripts/test sets up both).
Usage: scripts/render_docs_images.py [PICTURE ...]   (default: all; names as in docs/img without
.png, or "plots" for the plot_*.png)
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SINEW = ROOT / "build" / "sinew"
TOOLS = ROOT / "build" / "tests" / "browser"
SCREENSHOT = ROOT / "tests" / "browser" / "screenshot.mjs"
OUT = ROOT / "docs" / "img"

# picture name: (scene under examples/, changes to the scene, frames to run (None: the scene's),
# frame to show (-1: the last), field, controls bar shown). Pictures are docs/img/NAME.png.
EXAMPLES = {
    "viewer_page": ("features/obstacles_quasistatic", {}, None, 3, "von_mises", True),
    "example_stretch_small": ("stretch_small", {}, None, -1, "von_mises", False),
    "example_stretch_medium": ("stretch_medium", {}, None, -1, "von_mises", False),
    "example_stretch": ("stretch", {"mesh": {"cells": [14, 14, 18]}}, 12, -1, "von_mises", False),
    "example_twist": ("twist", {"mesh": {"cells": [8, 8, 8]}}, None, -1, "von_mises", False),
    "example_twist_fixed_corotational": ("twist_fixed_corotational", {"mesh": {"cells": [8, 8, 8]}}, None, -1, "J", False),
    "example_surface_embedding": ("surface_embedding", {}, None, -1, "von_mises", False),
    "example_elbow_cylinder": ("elbow_cylinder", {"mesh": {"cell_size": 0.02}}, None, -1, "von_mises", False),
    "example_elbow": ("elbow", {"mesh": {"cell_size": 0.02}}, None, -1, "von_mises", False),
    "example_drop_test": ("drop_test", {}, 20, -1, "von_mises", False),
    "example_beam_energy_limit": ("beam_energy_limit", {}, 12, -1, "von_mises", False),
    "example_falling_sphere": ("falling_sphere", {}, 30, -1, "von_mises", False),
    "example_collapsing_sphere": ("collapsing_sphere", {"mesh": {"resolution": 6}}, 20, -1, "J", False),
}


# Feature scenes (examples/features/NAME.json -> feature_NAME.png, 480 x 300) are all rendered at
# their own size and frame count; only these differ from (frame -1 = last, von Mises):
FEATURE_CHANGES = {
    "constraints_obstacles": ({}, 30, -1, "von_mises"),
    "material_functions": ({}, None, -1, "J"),
    "mesh_box_tet": ({}, None, -1, "J"),
}
for scene in sorted((ROOT / "examples" / "features").glob("*.json")):
    changes, frames, frame, field = FEATURE_CHANGES.get(scene.stem, ({}, None, -1, "von_mises"))
    EXAMPLES[f"feature_{scene.stem}"] = (f"features/{scene.stem}", changes, frames, frame, field, False)
PLOTS = {"plots": [str(ROOT / "scripts" / "make_plot_examples.sh")],
         "stress_stretch": [sys.executable, str(ROOT / "scripts" / "plot_material_curves.py")]}


def merge(scene, changes):
    for key, value in changes.items():
        if isinstance(value, dict) and isinstance(scene.get(key), dict):
            merge(scene[key], value)
        else:
            scene[key] = value


def render(picture, scene_name, changes, frames, frame, field, controls):
    source = ROOT / "examples" / f"{scene_name}.json"
    name = source.stem
    scene = json.loads(source.read_text())
    merge(scene, changes)
    with tempfile.TemporaryDirectory(prefix=f"sinew-docs-{name}-") as tmp:
        tmp = Path(tmp)
        # The scene's relative paths (meshes/, rigs/, ../meshes/) resolve against its folder:
        # mirror examples/ with links, the scene's own folder as a real one holding the small scene.
        examples = ROOT / "examples"
        mirror = tmp / "examples"
        mirror.mkdir()
        for entry in examples.iterdir():
            if entry != source.parent:
                (mirror / entry.name).symlink_to(entry)
        folder = mirror / source.parent.relative_to(examples)
        folder.mkdir(exist_ok=True)
        if source.parent != examples:
            for entry in source.parent.iterdir():
                (folder / entry.name).symlink_to(entry)
        small = folder / f"{name}.small.json"
        small.write_text(json.dumps(scene, indent=1))
        out = tmp / "out"
        run = [str(SINEW), "run", str(small), "--out", str(out), "--quiet"]
        if frames:
            run += ["--frames", str(frames)]
        subprocess.run(run, check=True)
        subprocess.run([str(SINEW), "viewer", str(small), "--out", str(out), "--quiet", "--title", scene_name], check=True)
        size = "640x480" if controls else "480x300" if picture.startswith("feature_") else "640x400"
        shot = ["node", str(SCREENSHOT), str(out / "viewer.html"), str(OUT / f"{picture}.png"), "--frame", str(frame),
                "--field", field, "--size", size]
        if controls:
            shot.append("--controls")
        subprocess.run(shot, check=True, env={**os.environ, "SINEW_BROWSER_TOOLS": str(TOOLS)})


def main():
    names = sys.argv[1:] or list(EXAMPLES) + list(PLOTS)
    unknown = [n for n in names if n not in EXAMPLES and n not in PLOTS]
    if unknown:
        sys.exit(f"render_docs_images: unknown picture(s) {', '.join(unknown)}; known: {', '.join(list(EXAMPLES) + list(PLOTS))}")
    for need, what in ((SINEW, "build/sinew (run scripts/setup)"), (TOOLS / "node_modules", "the browser test tools (run scripts/setup-browser-tests)")):
        if not need.exists():
            sys.exit(f"render_docs_images: {what} not found")
    if not shutil.which("node"):
        sys.exit("render_docs_images: node not found (Debian package nodejs)")
    OUT.mkdir(parents=True, exist_ok=True)
    for name in names:
        start = time.monotonic()
        if name in PLOTS:
            subprocess.run(PLOTS[name], check=True, cwd=ROOT)
        else:
            render(name, *EXAMPLES[name])
        print(f"render_docs_images: {name} in {time.monotonic() - start:.1f} s", flush=True)


if __name__ == "__main__":
    main()
