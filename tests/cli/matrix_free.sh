# `sinew run` with "hessian": "matrix_free": hexahedral and tetrahedral bars end where the
# assembled PCG run ends (energy, reactions); combinations that need the assembled matrix are
# rejected at load time with the field named.
source "$(dirname "$0")/common.bash"

scene() {  # ELEMENT LINEAR
  cat <<EOF2
{
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.25, 0.25, 1]}, "cells": [3, 3, 12], "element": "$1"},
  "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45},
  "boundary": [
    {"name": "bottom", "select": {"plane": {"point": [0, 0, 0], "normal": [0, 0, -1]}}},
    {"name": "top", "select": {"plane": {"point": [0, 0, 1], "normal": [0, 0, 1]}},
     "motion": {"type": "translate", "per_frame": [0.05, 0, 0.1]}}
  ],
  "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-6}, "linear": $2},
  "frames": 2
}
EOF2
}
for run in hex:block_jacobi hex:multigrid tet:block_jacobi; do
  element=${run%%:*} preconditioner=${run#*:}
  scene $element '{"kind": "pcg", "tolerance": 1e-8, "preconditioner": "'$preconditioner'", "hessian": "matrix_free"}' >"$TMP/free.json"
  scene $element '{"kind": "pcg", "tolerance": 1e-8}' >"$TMP/assembled.json"
  expect_ok run "$TMP/free.json" --out "$TMP/free" --quiet
  expect_ok run "$TMP/assembled.json" --out "$TMP/assembled" --quiet
  "$PY" - "$TMP/free/summary.json" "$TMP/assembled/summary.json" <<'EOF2' ||
import json, sys
free, assembled = (json.load(open(p)) for p in sys.argv[1:3])
assert free["all_converged"] and free["frames_completed"] == 2, free
a, d = free["frames"][-1], assembled["frames"][-1]
assert abs(a["energy"] - d["energy"]) <= 1e-7 * abs(d["energy"]), (a["energy"], d["energy"])
for ra, rd in zip(a["reactions"], d["reactions"]):
    assert max(abs(x - y) for x, y in zip(ra, rd)) <= 1e-4 * max(abs(y) for y in rd), (ra, rd)
EOF2
    fail "$run: matrix-free and assembled runs differ: $(cat "$TMP/free/summary.json")"
done

scene hex '{"kind": "cholmod", "hessian": "matrix_free"}' >"$TMP/bad.json"
expect_error "/solver/linear/hessian" run "$TMP/bad.json" --out "$TMP/bad" --quiet
scene hex '{"kind": "pcg", "preconditioner": "lagged_cholesky", "hessian": "matrix_free"}' >"$TMP/bad.json"
expect_error "/solver/linear/hessian" run "$TMP/bad.json" --out "$TMP/bad" --quiet
scene hex '{"kind": "pcg", "hessian": "dense"}' >"$TMP/bad.json"
expect_error "/solver/linear/hessian" run "$TMP/bad.json" --out "$TMP/bad" --quiet
[[ ! -e $TMP/bad ]] || fail "a rejected scene left an output folder"
# Energy-limited dynamics factorises its matrices: refused too.
examples=$(cd "$(dirname "$0")/../../examples" && pwd)
"$PY" - "$examples/falling_sphere.json" "$TMP/constrained.json" "$examples" <<'EOF2'
import json, sys
d = json.load(open(sys.argv[1]))
d["mesh"]["file"] = sys.argv[3] + "/" + d["mesh"]["file"]
d.setdefault("solver", {})["linear"] = {"kind": "pcg", "hessian": "matrix_free"}
json.dump(d, open(sys.argv[2], "w"))
EOF2
expect_error "/solver/linear/hessian" run "$TMP/constrained.json" --out "$TMP/bad" --quiet
echo "matrix_free: ok"
