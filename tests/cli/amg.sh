# `sinew run` with the "amg" preconditioner (hypre BoomerAMG): a tetrahedral bar (no lattice
# grid, so geometric multigrid could not coarsen it) converges every frame and ends where
# CHOLMOD's run ends (energy, reactions); MPI starts without mpirun and nothing is left on stderr.
source "$(dirname "$0")/common.bash"

scene() {
  cat <<EOF2
{
  "mesh": {"box": {"min": [0, 0, 0], "max": [0.25, 0.25, 1]}, "cells": [3, 3, 12], "element": "tet"},
  "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.49},
  "boundary": [
    {"name": "bottom", "select": {"plane": {"point": [0, 0, 0], "normal": [0, 0, -1]}}},
    {"name": "top", "select": {"plane": {"point": [0, 0, 1], "normal": [0, 0, 1]}},
     "motion": {"type": "translate", "per_frame": [0.05, 0, -0.05]}}
  ],
  "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-6}, "linear": $1},
  "frames": 2
}
EOF2
}
scene '{"kind": "pcg", "preconditioner": "amg", "tolerance": 1e-8}' >"$TMP/amg.json"
scene '{"kind": "cholmod"}' >"$TMP/direct.json"

run run "$TMP/amg.json" --out "$TMP/amg" --quiet
[[ $RC -eq 0 ]] || fail "amg.json exited $RC: $(cat "$TMP/err")"
[[ ! -s $TMP/err ]] || fail "amg run wrote to stderr: $(cat "$TMP/err")"
run run "$TMP/direct.json" --out "$TMP/direct" --quiet
[[ $RC -eq 0 ]] || fail "direct.json exited $RC: $(cat "$TMP/err")"

"$PY" - "$TMP/amg/summary.json" "$TMP/direct/summary.json" <<'EOF2' ||
import json, sys
amg, direct = (json.load(open(p)) for p in sys.argv[1:3])
assert amg["all_converged"] and amg["frames_completed"] == 2, amg
assert amg["total_linear_iterations"] > 0  # PCG ran (CHOLMOD counts none)
a, d = amg["frames"][-1], direct["frames"][-1]
assert abs(a["energy"] - d["energy"]) <= 1e-8 * abs(d["energy"]), (a["energy"], d["energy"])
for ra, rd in zip(a["reactions"], d["reactions"]):
    assert max(abs(x - y) for x, y in zip(ra, rd)) <= 1e-5 * max(abs(y) for y in rd), (ra, rd)
EOF2
  fail "amg run's summary or result: $(cat "$TMP/amg/summary.json")"
echo "amg: ok"
