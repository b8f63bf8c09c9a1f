# `sinew run` with a `dynamics` section and obstacles: bad input exits 2 with one line naming
# file, JSON path and reason and writes nothing; a small drop runs and its summary.json carries
# the per-frame kinetic/potential energy and contact counts.
source "$(dirname "$0")/common.bash"

MESH='"mesh": {"box": {"min": [0, 0, 0.02], "max": [0.2, 0.2, 0.22]}, "cells": [2, 2, 2]}'
MAT='"material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45}'

scene_error "/dynamics/time_step: required field is missing" "{$MESH, $MAT, \"dynamics\": {}}"
scene_error "/dynamics/integrator: unknown value 'explicit'" "{$MESH, $MAT, \"dynamics\": {\"time_step\": 0.01, \"integrator\": \"explicit\"}}"
scene_error "/dynamics/rayleigh/alpha: must be >= 0" "{$MESH, $MAT, \"dynamics\": {\"time_step\": 0.01, \"rayleigh\": {\"alpha\": -2}}}"
scene_error "/obstacles/0/type: unknown value 'cone'" "{$MESH, $MAT, \"obstacles\": [{\"type\": \"cone\", \"stiffness\": 1}]}"
scene_error "/obstacles/0/stiffness: must be a positive" "{$MESH, $MAT, \"obstacles\": [{\"type\": \"plane\", \"point\": [0,0,0], \"normal\": [0,0,1], \"stiffness\": 0}]}"
scene_error "/obstacles/0/friction: friction needs a \`dynamics\` section" "{$MESH, $MAT, \"obstacles\": [{\"type\": \"plane\", \"point\": [0,0,0], \"normal\": [0,0,1], \"stiffness\": 1e6, \"friction\": 0.5}]}"

dir=$TMP/drop
mkdir -p "$dir"
printf '%s\n' "{$MESH, $MAT, \"loads\": {\"gravity\": [0, 0, -9.81]},
  \"dynamics\": {\"time_step\": 0.02, \"substeps\": 2},
  \"obstacles\": [{\"name\": \"ground\", \"type\": \"plane\", \"point\": [0,0,0], \"normal\": [0,0,1], \"stiffness\": 1e7, \"friction\": 0.3}],
  \"frames\": 10}" >"$dir/scene.json"
expect_ok run "$dir/scene.json" --out "$dir/out" --quiet
"$PY" - "$dir/out/summary.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["all_converged"] and d["frames_completed"] == 10, d
f = d["frames"]
assert all(k in f[0] for k in ("kinetic_energy", "potential_energy", "contacts", "max_penetration"))
assert f[0]["contacts"] == 0 and f[-1]["contacts"] > 0, [x["contacts"] for x in f]
assert max(x["kinetic_energy"] for x in f) > 0
assert all(x["substeps"] == 2 for x in f)
PY
echo "dynamics: ok ($CASE error cases, drop run)"
