# `sinew check`: every example scene's energy terms pass the derivative check at the scene's
# first-frame state; a previous run's checkpoint can be checked; a too-strict tolerance fails with
# exit 3; bad input is exit 2 naming the option or file.
source "$(dirname "$0")/common.bash"
EXAMPLES=$(cd "$(dirname "$0")/../../examples" && pwd)

count=0
for scene in "$EXAMPLES"/*.json "$EXAMPLES"/features/*.json; do
  name=$(basename "$scene" .json)
  # Paper 000's full-size stretch (about 230k hexahedra) takes minutes; stretch_small and
  # stretch_medium are the same scene smaller.
  [[ $name == stretch ]] && continue
  run check "$scene"
  [[ $RC -eq 0 ]] || fail "check $name exited $RC: $(cat "$TMP/out") $(cat "$TMP/err")"
  grep -Eq '^(elastic|corotational-hex) .* pass$' "$TMP/out" || fail "check $name: no passing elastic row: $(cat "$TMP/out")"
  ! grep -q 'FAIL' "$TMP/out" || fail "check $name: a row failed: $(cat "$TMP/out")"
  count=$((count + 1))
done
[[ $count -ge 40 ]] || fail "only $count example scenes found in $EXAMPLES"

# A row per energy term: gravity (external), obstacles (contact) and dynamics (inertia).
expect_ok check "$EXAMPLES/features/dynamics_obstacles.json"
for form in elastic external contact inertia; do
  grep -q "^$form " "$TMP/out" || fail "dynamics_obstacles: no row for $form: $(cat "$TMP/out")"
done

# The seed changes the state; the same seed gives the same table.
expect_ok check "$EXAMPLES/features/load_gravity.json" --seed 7
cp "$TMP/out" "$TMP/seed7"
expect_ok check "$EXAMPLES/features/load_gravity.json" --seed 7
cmp -s "$TMP/out" "$TMP/seed7" || fail "same seed, different output"
grep -q 'seed 7' "$TMP/out" || fail "the seed is not reported"

# At a run's checkpoint.
run run "$EXAMPLES/features/motion_rotate.json" --out "$TMP/rotate" --frames 1 --quiet
[[ $RC -eq 0 ]] || fail "run motion_rotate exited $RC: $(cat "$TMP/err")"
expect_ok check "$EXAMPLES/features/motion_rotate.json" --state "$TMP/rotate"
grep -q 'checkpoint of frame 1' "$TMP/out" || fail "--state not reported: $(cat "$TMP/out")"

# Failing terms: exit 3, the failing rows marked, one line on stderr.
run check "$EXAMPLES/features/load_gravity.json" --tolerance 1e-300
[[ $RC -eq 3 ]] || fail "too strict a tolerance exited $RC (expected 3)"
grep -q 'FAIL' "$TMP/out" || fail "no FAIL row: $(cat "$TMP/out")"
[[ $(wc -l <"$TMP/err") -eq 1 ]] || fail "expected one stderr line: $(cat "$TMP/err")"

# Bad input.
expect_error "missing.json" check "$TMP/missing.json"
expect_error "--seed" check "$EXAMPLES/features/load_gravity.json" --seed -1
expect_error "--seed" check "$EXAMPLES/features/load_gravity.json" --seed x
expect_error "--tolerance" check "$EXAMPLES/features/load_gravity.json" --tolerance 0
expect_error "checkpoint.json" check "$EXAMPLES/features/load_gravity.json" --state "$TMP/nowhere"
mkdir -p "$TMP/bad"
echo '{"x": [1, 2, 3]}' >"$TMP/bad/checkpoint.json"
expect_error "DOFs" check "$EXAMPLES/features/load_gravity.json" --state "$TMP/bad"
echo '{"x": ' >"$TMP/bad/checkpoint.json"
expect_error "checkpoint.json: malformed JSON" check "$EXAMPLES/features/load_gravity.json" --state "$TMP/bad"
echo "check: ok ($count scenes)"
