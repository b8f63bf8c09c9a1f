# `sinew run`: output files, where-results line, progress (one plain line per frame when stderr
# is not a terminal or with --progress=plain, a live line per frame redrawn in place on a
# terminal, per-iteration lines with --verbose, nothing with --quiet), exit code 3 for a frame
# that did not converge, --resume, stale files of an earlier run, and two runs into one folder.
source "$(dirname "$0")/common.bash"
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
SINEW=$(realpath "$SINEW")

cat >"$TMP/bar.json" <<'EOF'
{
  "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.25, 0.25]}, "cells": [8, 2, 2]},
  "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45},
  "boundary": [
    {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
    {"name": "right", "select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}},
     "motion": {"type": "translate", "per_frame": [0.1, 0, 0]}}
  ],
  "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-6}},
  "frames": 4
}
EOF

expect_ok run --help
for flag in --out --frames --threads --progress --verbose --quiet --resume --checkpoint-seconds scene-format.md; do
  grep -q -- "$flag" "$TMP/out" || fail "run --help lacks $flag"
done

# Plain progress lines on a non-terminal stderr; results line on stdout.
run run "$TMP/bar.json" --out "$TMP/a"
[[ $RC -eq 0 ]] || fail "bar.json exited $RC: $(cat "$TMP/err")"
grep -q "^frame 4/4: [0-9]* Newton, [0-9]* linear iterations, residual .*, elapsed [0-9.]* s$" "$TMP/err" ||
  fail "no per-frame line: $(cat "$TMP/err")"
grep -q "^frame 3/4: .*, elapsed [0-9.]* s, ETA [0-9.]* s$" "$TMP/err" || fail "no ETA on frame 3: $(cat "$TMP/err")"
[[ $(wc -l <"$TMP/err") -eq 4 ]] || fail "expected one progress line per frame: $(cat "$TMP/err")"
if grep -q $'\r\|\033' "$TMP/err"; then fail "terminal control characters in non-terminal output"; fi
grep -q "^results in $TMP/a " "$TMP/out" || fail "no results line: $(cat "$TMP/out")"
grep -q "^81 vertices, 32 elements, 4 frame(s)" "$TMP/out" || fail "no size line: $(cat "$TMP/out")"
for f in simulation.pvd summary.json frames.jsonl checkpoint.json frame_0000.vtu frame_0004.vtu surface_0000.obj surface_0004.obj; do
  [[ -s $TMP/a/$f ]] || fail "missing output $f"
done
if ls -A "$TMP/a" | grep -q -v -E '^(simulation\.pvd|summary\.json|frames\.jsonl|checkpoint\.json|frame_000[0-4]\.vtu|surface_000[0-4]\.obj)$'; then
  fail "unexpected files (temporaries left behind?): $(ls -A "$TMP/a")"
fi
grep -c "<DataSet " "$TMP/a/simulation.pvd" | grep -qx 5 || fail "simulation.pvd does not list 5 frames"
"$PY" - "$TMP/a/summary.json" <<'EOF' || fail "summary.json content"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["all_converged"] and d["frames_completed"] == 4 and d["frames_requested"] == 4, d
assert d["vertices"] == 81 and d["elements"] == 32 and d["element"] == "hex8", d
assert d["boundary"] == ["left", "right"]
for i, f in enumerate(d["frames"], 1):
    assert f["frame"] == i and f["converged"] and f["failure"] == ""
    assert f["newton_iterations"] >= 1 and f["linear_iterations"] >= f["newton_iterations"]
    assert 0 <= f["residual"] < 1e-6
    for key in ("energy", "volume", "min_J", "seconds", "assembly_seconds", "solve_seconds"):
        assert isinstance(f[key], float), key
    left, right = f["reactions"]
    assert right[0] > 0 and abs(left[0] + right[0]) < 1e-5 * right[0], f["reactions"]
# Stretching pulls harder every frame.
pulls = [f["reactions"][1][0] for f in d["frames"]]
assert pulls == sorted(pulls), pulls
EOF

# --verbose adds one line per Newton iteration.
run run "$TMP/bar.json" --out "$TMP/v" --frames 2 --verbose
[[ $RC -eq 0 ]] || fail "--verbose exited $RC: $(cat "$TMP/err")"
grep -q "^frame 1/2 Newton 1 residual [0-9.e+-]* elapsed [0-9.]* s$" "$TMP/err" || fail "no per-iteration line: $(cat "$TMP/err")"
grep -q "^frame 2/2: " "$TMP/err" || fail "--verbose lost the frame line: $(cat "$TMP/err")"
expect_error "--progress" run "$TMP/bar.json" --out "$TMP/v" --progress fancy

# --quiet: nothing on stdout or stderr, same files.
expect_ok run "$TMP/bar.json" --out "$TMP/q" --quiet
[[ ! -s $TMP/out ]] || fail "--quiet wrote to stdout: $(cat "$TMP/out")"
cmp -s "$TMP/a/frame_0004.vtu" "$TMP/q/frame_0004.vtu" || fail "--quiet changed the result"

# A terminal gets one live line per frame, redrawn in place (Newton iteration, residual,
# elapsed, ETA from the second frame on) and left as the frame's line; --progress=plain there
# gives the plain lines.
if command -v script >/dev/null; then
  script -qec "'$SINEW' run '$TMP/bar.json' --out '$TMP/tty' --frames 3" /dev/null >"$TMP/tty.txt" </dev/null
  grep -q $'\r\033\[Kframe 1/3  Newton 1  residual [0-9.e+-]*  elapsed [0-9.]* s' "$TMP/tty.txt" ||
    fail "no live progress on a terminal: $(cat -v "$TMP/tty.txt")"
  grep -q $'\r\033\[Kframe 2/3  Newton 1  residual [0-9.e+-]*  elapsed [0-9.]* s  ETA [0-9.]* s' "$TMP/tty.txt" ||
    fail "no ETA in the live line: $(cat -v "$TMP/tty.txt")"
  grep -q $'\r\033\[Kframe 3/3: [0-9]* Newton' "$TMP/tty.txt" || fail "no frame line on a terminal: $(cat -v "$TMP/tty.txt")"
  grep -q "results in" "$TMP/tty.txt" || fail "no results line on a terminal"
  script -qec "'$SINEW' run '$TMP/bar.json' --out '$TMP/tty' --frames 2 --progress=plain" /dev/null >"$TMP/tty.txt" </dev/null
  if grep -q $'\033' "$TMP/tty.txt"; then fail "--progress=plain drew on the terminal: $(cat -v "$TMP/tty.txt")"; fi
  grep -q "^frame 2/2: " "$TMP/tty.txt" || fail "--progress=plain on a terminal: $(cat -v "$TMP/tty.txt")"
fi

# --resume: 2 of 4 frames, then resume to 4, equals the uninterrupted run bit for bit.
expect_ok run "$TMP/bar.json" --out "$TMP/r" --frames 2 --quiet
[[ ! -e $TMP/r/frame_0003.vtu ]] || fail "--frames 2 wrote frame 3"
expect_ok run "$TMP/bar.json" --out "$TMP/r" --resume --quiet
cmp -s "$TMP/a/frame_0004.vtu" "$TMP/r/frame_0004.vtu" || fail "resumed run differs from the uninterrupted one"
grep -c "<DataSet " "$TMP/r/simulation.pvd" | grep -qx 5 || fail "resumed simulation.pvd does not list 5 frames"
"$PY" -c "import json,sys; d=json.load(open(sys.argv[1])); assert [f['frame'] for f in d['frames']] == [1,2,3,4], d['frames']" \
  "$TMP/r/summary.json" || fail "resumed summary.json frames"
# --checkpoint-seconds 0 checkpoints every frame, a long interval only the last one; both resume.
expect_ok run "$TMP/bar.json" --out "$TMP/c0" --frames 2 --checkpoint-seconds 0 --quiet
expect_ok run "$TMP/bar.json" --out "$TMP/c0" --resume --checkpoint-seconds 1e6 --quiet
cmp -s "$TMP/a/frame_0004.vtu" "$TMP/c0/frame_0004.vtu" || fail "run resumed with --checkpoint-seconds differs"
"$PY" -c "import json,sys; assert json.load(open(sys.argv[1]))['frame'] == 4" "$TMP/c0/checkpoint.json" ||
  fail "the last frame was not checkpointed"
expect_error "--checkpoint-seconds: expected a number, got 'soon'" run "$TMP/bar.json" --out "$TMP/c1" --checkpoint-seconds soon
expect_error "--checkpoint-seconds: must be a finite number of seconds >= 0" run "$TMP/bar.json" --out "$TMP/c1" --checkpoint-seconds=-1
# A changed scene cannot be resumed.
sed 's/"frames": 4/"frames": 5/' "$TMP/bar.json" >"$TMP/bar5.json"
cp "$TMP/r/checkpoint.json" "$TMP/cp.json"
expect_error "the scene file changed" run "$TMP/bar5.json" --out "$TMP/r" --resume

# A fresh run replaces an earlier run's files, leaving no stale frames.
expect_ok run "$TMP/bar.json" --out "$TMP/a" --frames 1 --quiet
[[ ! -e $TMP/a/frame_0002.vtu && ! -e $TMP/a/surface_0004.obj ]] || fail "stale frames left: $(ls "$TMP/a")"
touch "$TMP/a/notes.txt"
expect_ok run "$TMP/bar.json" --out "$TMP/a" --frames 1 --quiet
[[ -e $TMP/a/notes.txt ]] || fail "a fresh run removed a file it did not write"

# A frame that does not converge: reported, exit 3, run stopped there, never silently accepted.
sed -e 's/"tolerance": 1e-6}/"tolerance": 1e-9, "max_iterations": 1}/' -e 's/0.1, 0, 0/0.8, 0, 0/' "$TMP/bar.json" >"$TMP/hard.json"
run run "$TMP/hard.json" --out "$TMP/h"
[[ $RC -eq 3 ]] || fail "non-converging run exited $RC (expected 3): $(cat "$TMP/err")"
grep -q "^sinew: frame 1 did not converge: no convergence in 1 Newton iterations" "$TMP/err" || fail "no failure line: $(cat "$TMP/err")"
grep -q "NOT CONVERGED" "$TMP/err" || fail "progress does not flag the frame"
"$PY" - "$TMP/h/summary.json" <<'EOF' || fail "summary.json of a failed run"
import json, sys
d = json.load(open(sys.argv[1]))
assert not d["all_converged"] and d["frames_completed"] == 1 and d["frames_requested"] == 4, d
f = d["frames"][0]
assert not f["converged"] and "no convergence" in f["failure"] and f["residual"] > 1e-9, f
EOF
[[ -e $TMP/h/frame_0001.vtu && ! -e $TMP/h/frame_0002.vtu ]] || fail "failed frame not written, or the run went on"
[[ ! -e $TMP/h/checkpoint.json ]] || fail "a checkpoint was written for an unconverged frame"
run run "$TMP/hard.json" --out "$TMP/h2" --quiet
[[ $RC -eq 3 && ! -s $TMP/out ]] || fail "--quiet non-converging run: exit $RC"
grep -q "did not converge" "$TMP/err" || fail "--quiet hid the failure"

# Two runs into one folder: the second is refused naming the folder and the first run's pid;
# the first goes on and finishes. A killed run's lock does not outlive it.
sed 's/"frames": 4/"frames": 100000/' "$TMP/bar.json" >"$TMP/long.json"
"$SINEW" run "$TMP/long.json" --out "$TMP/shared" --quiet >/dev/null 2>&1 &
first=$!
for _ in $(seq 300); do [[ -s $TMP/shared/frame_0001.vtu ]] && break; sleep 0.1; done
[[ -s $TMP/shared/frame_0001.vtu ]] || fail "the first run wrote no frame"
expect_error "$TMP/shared: output folder is in use by another sinew run (pid $first)" run "$TMP/bar.json" --out "$TMP/shared"
expect_error "(pid $first)" run "$TMP/long.json" --out "$TMP/shared" --resume
kill -0 "$first" 2>/dev/null || fail "the first run did not go on"
kill -KILL "$first"
wait "$first" 2>/dev/null || true
expect_ok run "$TMP/bar.json" --out "$TMP/shared" --quiet
[[ ! -e $TMP/shared/.sinew.lock && ! -e $TMP/shared/frame_0005.vtu ]] || fail "lock or the killed run's frames left: $(ls -A "$TMP/shared")"

# README command 1: the default scene, results under out/<scene name> of the working folder.
mkdir -p "$TMP/cwd"
(cd "$TMP/cwd" && "$SINEW" run "$ROOT/examples/stretch_small.json" >"$TMP/out" 2>"$TMP/err") || fail "stretch_small: $(cat "$TMP/err")"
grep -q "^results in out/stretch_small " "$TMP/out" || fail "stretch_small results line: $(cat "$TMP/out")"
[[ -s $TMP/cwd/out/stretch_small/frame_0004.vtu ]] || fail "stretch_small wrote no frame 4"
"$PY" -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['all_converged'] and d['frames_completed'] == 4" \
  "$TMP/cwd/out/stretch_small/summary.json" || fail "stretch_small did not converge"
echo "run: ok"
