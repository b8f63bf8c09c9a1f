#!/usr/bin/env bash
# Regenerates the plots of docs/python.md (docs/img/python_*.png) by running its two worked
# examples (examples/python/) with the built module. About a minute; needs a build (scripts/setup).
set -euo pipefail
cd "$(dirname "$0")/.."
export PYTHONPATH=build/python MPLBACKEND=Agg
/usr/bin/python3 examples/python/material_sweep.py --out docs/img/python_material_sweep.png
/usr/bin/python3 examples/python/stretch_frame_by_frame.py --out docs/img/python_stretch.png
