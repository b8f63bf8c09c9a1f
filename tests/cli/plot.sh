# `sinew plot OUT_DIR`: a quasistatic and a dynamic run plotted as PNG and SVG (valid files of a
# plausible size), and bad input named with its file and reason (exit 2).
source "$(dirname "$0")/common.bash"

# Every plot file is a real image: the PNG signature or an SVG document, and not a stub.
check_images() {
  local dir=$1
  shift
  for name in "$@"; do
    for ext in png svg; do
      local f=$dir/$name.$ext
      [[ -f $f ]] || fail "missing $f"
      [[ $(stat -c %s "$f") -gt 8000 ]] || fail "$f is only $(stat -c %s "$f") bytes"
    done
    "$PY" - "$dir/$name.png" "$dir/$name.svg" <<'PYEOF' || fail "$name: not a valid PNG/SVG"
import struct, sys, xml.etree.ElementTree as ET
png = open(sys.argv[1], "rb").read()
assert png[:8] == b"\x89PNG\r\n\x1a\n", "PNG signature"
assert png[12:16] == b"IHDR"
width, height = struct.unpack(">II", png[16:24])
assert width >= 300 and height >= 200, (width, height)
root = ET.parse(sys.argv[2]).getroot()
assert root.tag.endswith("svg"), root.tag
PYEOF
  done
}

mkdir -p "$TMP/q"
cat >"$TMP/q/stretch.json" <<'JSON'
{"mesh": {"box": {"min": [0, 0, 0], "max": [2, 0.5, 0.5]}, "cells": [4, 1, 1]},
 "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45},
 "boundary": [{"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
              {"name": "right", "select": {"plane": {"point": [2, 0, 0], "normal": [1, 0, 0]}},
               "motion": {"type": "translate", "per_frame": [0.2, 0, 0]}}],
 "output": {"vtu": false, "obj": false},
 "frames": 3}
JSON
expect_ok run "$TMP/q/stretch.json" --out "$TMP/q/out" --quiet
expect_ok plot "$TMP/q/out"
check_images "$TMP/q/out/plots" convergence reactions volume energy stress_stretch
[[ $(wc -l <"$TMP/out") -eq 10 ]] || fail "plot should list 10 files: $(cat "$TMP/out")"

# Each frame records its residual after every Newton iteration; the convergence plot reads them
# (one curve per frame).
"$PY" - "$TMP/q/out/summary.json" "$(dirname "$0")/../../scripts" <<'PYEOF' || fail "per-iteration residuals"
import json, sys
d = json.load(open(sys.argv[1]))
for f in d["frames"]:
    assert len(f["residuals"]) == f["newton_iterations"] >= 1, f
    assert f["residuals"][-1] == f["residual"], f
sys.path.insert(0, sys.argv[2])
import sinew_plot
run = sinew_plot.read_summary(sys.argv[1])
assert run.residual_history == [f["residuals"] for f in d["frames"]]
PYEOF

# --plots, --format and --only.
expect_ok plot "$TMP/q/out" --plots "$TMP/q/only" --format svg --only volume,reactions
[[ -f $TMP/q/only/volume.svg && -f $TMP/q/only/reactions.svg ]] || fail "--only/--format files"
[[ $(ls "$TMP/q/only" | wc -l) -eq 2 ]] || fail "--only wrote other plots: $(ls "$TMP/q/only")"

# Dynamics: energy over time (kinetic and potential), no boundary so no reactions plot.
mkdir -p "$TMP/d"
cat >"$TMP/d/drop.json" <<'JSON'
{"mesh": {"box": {"min": [-0.1, -0.1, 0.05], "max": [0.1, 0.1, 0.15]}, "cells": [2, 2, 1]},
 "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
 "loads": {"gravity": [0, 0, -9.81]},
 "dynamics": {"time_step": 0.02},
 "obstacles": [{"name": "ground", "type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1], "stiffness": 1e7}],
 "output": {"vtu": false, "obj": false},
 "frames": 4}
JSON
expect_ok run "$TMP/d/drop.json" --out "$TMP/d/out" --quiet
run plot "$TMP/d/out" --only energy,convergence,reactions
[[ $RC -eq 0 ]] || fail "dynamic plot exited $RC: $(cat "$TMP/err")"
grep -q "reactions skipped" "$TMP/err" || fail "no note for the skipped reactions plot: $(cat "$TMP/err")"
check_images "$TMP/d/out/plots" energy convergence

# The scene file gone: the material plot is skipped with a note, the others are drawn.
cp -r "$TMP/q/out" "$TMP/moved"
sed -i 's#"scene": "[^"]*"#"scene": "/nonexistent/stretch.json"#' "$TMP/moved/summary.json"
run plot "$TMP/moved" --only stress_stretch,volume
[[ $RC -eq 0 ]] || fail "plot without the scene exited $RC"
grep -q "stress_stretch skipped: scene file /nonexistent/stretch.json not found" "$TMP/err" || fail "note: $(cat "$TMP/err")"

# Bad input: each names the file (or flag) and the reason, exit 2, nothing on stdout.
expect_error "$TMP/none: no such output folder" plot "$TMP/none"
expect_error "not a folder" plot "$TMP/q/stretch.json"
mkdir -p "$TMP/empty"
expect_error "$TMP/empty/summary.json: no summary.json" plot "$TMP/empty"
mkdir -p "$TMP/bad"
printf '{"frames": [\n  {"frame": 1,\n' >"$TMP/bad/summary.json"
expect_error "$TMP/bad/summary.json:3: malformed JSON" plot "$TMP/bad"
echo '{"frames": {}}' >"$TMP/bad/summary.json"
expect_error "summary.json: \"frames\" must be a list" plot "$TMP/bad"
echo '{"frames": []}' >"$TMP/bad/summary.json"
expect_error "no completed frame" plot "$TMP/bad"
echo '{"frames": [{"frame": 1, "converged": true, "newton_iterations": 2, "linear_iterations": 3, "volume": "big", "residual": 0}]}' >"$TMP/bad/summary.json"
expect_error "summary.json: /frames/0: \"volume\" must be float" plot "$TMP/bad"
echo '{"frames": [{"frame": 1, "converged": true, "linear_iterations": 3, "volume": 1, "residual": 0}]}' >"$TMP/bad/summary.json"
expect_error "/frames/0: missing \"newton_iterations\"" plot "$TMP/bad"
expect_error "--format: unknown format 'gif'" plot "$TMP/q/out" --format gif
expect_error "--only: unknown plot 'pressure'" plot "$TMP/q/out" --only pressure
expect_error "out_dir is required" plot
echo "plot: ok"
