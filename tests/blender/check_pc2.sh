#!/usr/bin/env bash
# Blender check (CTest label `blender`, not in scripts/test's default run: Debian's blender is a
# large install). Runs Sinew on a quad render cube and on the elbow example (2 frames), then has
# a real Blender import each rest OBJ, add a Mesh Cache modifier with the .pc2 and compare its
# evaluated vertex positions with Sinew's per-frame OBJs (tests/blender/check_pc2.py). Finally a
# cache with two samples swapped must be rejected, so the check can fail.
# usage: check_pc2.sh /path/to/sinew          exit 77 (skipped) when blender is not installed
set -euo pipefail
SINEW=${1:?usage: check_pc2.sh /path/to/sinew}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
BLENDER=${BLENDER:-blender}
command -v "$BLENDER" >/dev/null || { echo "check_pc2: $BLENDER not found (Debian package blender): skipped"; exit 77; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

blender_check() {
  "$BLENDER" -b --factory-startup --python-exit-code 1 --python "$HERE/check_pc2.py" -- "$@" >"$TMP/blender.log" 2>&1
}

cat >"$TMP/cube.json" <<JSON
{"description": "quad render cube embedded in a box lattice, sheared by its pulled top face",
 "mesh": {"box": {"min": [-0.6, -0.6, -0.6], "max": [0.6, 0.6, 0.6]}, "cells": [3, 3, 3],
          "embed": "$ROOT/tests/data/render/cube_quads.obj"},
 "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
 "boundary": [{"name": "base", "select": {"plane": {"point": [0, 0, -0.6], "normal": [0, 0, -1]}}},
              {"name": "top", "select": {"plane": {"point": [0, 0, 0.6], "normal": [0, 0, 1]}},
               "motion": {"type": "translate", "per_frame": [0.08, 0, 0.03]}}],
 "frames": 3}
JSON
"$SINEW" run "$TMP/cube.json" --out "$TMP/cube" --quiet
blender_check "$TMP/cube" --frames 0,1,2,3 || { cat "$TMP/blender.log"; echo "FAIL: cube"; exit 1; }
grep '^check_pc2' "$TMP/blender.log"

"$SINEW" run "$ROOT/examples/elbow.json" --out "$TMP/elbow" --frames 2 --quiet
blender_check "$TMP/elbow" --frames 0,1,2 || { cat "$TMP/blender.log"; echo "FAIL: elbow"; exit 1; }
grep '^check_pc2' "$TMP/blender.log"

# Samples 1 and 2 swapped: Blender then shows frame 2 at frame 1, which the check must catch.
/usr/bin/python3 - "$TMP/cube/embedded_surface.pc2" <<'PY'
import struct, sys
data = bytearray(open(sys.argv[1], "rb").read())
points = struct.unpack_from("<i", data, 16)[0]
n = points * 12
s1, s2 = 32 + n, 32 + 2 * n
data[s1:s1 + n], data[s2:s2 + n] = data[s2:s2 + n], data[s1:s1 + n]
open(sys.argv[1], "wb").write(data)
PY
if blender_check "$TMP/cube" --frames 0,1,2,3; then echo "FAIL: a cache with swapped samples passed"; exit 1; fi
grep -q "frame 1: Blender's Mesh Cache positions differ" "$TMP/blender.log" || { cat "$TMP/blender.log"; echo "FAIL: wrong failure"; exit 1; }
echo "check_pc2: ok"
