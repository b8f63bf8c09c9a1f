# `sinew material curve`: CSV / text / JSON shapes and the small-strain slope E.
source "$(dirname "$0")/common.bash"

expect_ok material curve --material linear_corotational --E 1e5 --nu 0.45 \
  --stretch-from 0.9 --stretch-to 1.1 --steps 4 --csv
[[ $(head -1 "$TMP/out") == "stretch,lateral_stretch,J,stress,psi" ]] || fail "CSV header"
[[ $(wc -l <"$TMP/out") -eq 6 ]] || fail "expected 5 CSV rows"
"$PY" -c '
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for r in rows:
    s, t, J, P = (float(r[k]) for k in ("stretch", "lateral_stretch", "J", "stress"))
    assert abs(P - 1e5 * (s - 1)) <= 1e-6, r             # linear corotational: exactly E (s - 1)
    assert abs(t - (1 - 0.45 * (s - 1))) <= 1e-12, r      # and nu (s - 1) lateral contraction
    assert abs(J - s * t * t) <= 1e-12, r
' "$TMP/out" || fail "uniaxial values"

for mode in uniaxial biaxial shear; do
  expect_ok material curve --material linear_corotational --mode $mode --stretch-from 0.8 \
    --stretch-to 1.3 --steps 5 --json
  json_check '
assert len(d["points"]) == 6
assert d["points"][0]["stretch"] == 0.8 and d["points"][-1]["stretch"] == 1.3
for p in d["points"]:
    assert set(p) == {"stretch", "lateral_stretch", "J", "stress", "psi"}
'
done

expect_ok material curve --material linear_corotational --alpha 2 --steps 3
grep -q "uniaxial curve" "$TMP/out" || fail "text header"
[[ $(grep -cE '^ +[0-9.]+ ' "$TMP/out") -eq 4 ]] || fail "text rows: $(cat "$TMP/out")"

expect_ok material curve --mix-lambda linear_corotational --mix-mu linear_corotational \
  --E 10 --nu 0.3 --alpha-mu 3 --steps 2 --csv
[[ $(wc -l <"$TMP/out") -eq 4 ]] || fail "mix curve rows"
# --material-json: a scene's /material object, the same curve as the flags give.
expect_ok material curve --material-json '{"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45}' --steps 4 --csv
cp "$TMP/out" "$TMP/from_json.csv"
expect_ok material curve --material stable_neo_hookean --E 1e5 --nu 0.45 --steps 4 --csv
cmp -s "$TMP/out" "$TMP/from_json.csv" || fail "--material-json curve differs from the flags' curve"
expect_error "--material-json: malformed JSON" material curve --material-json '{"family":'
expect_error "--material-json/nu" material curve --material-json '{"family": "stable_neo_hookean", "E": 1e5, "nu": 0.7}'
expect_error "--material-json: describes the whole material" material curve --material-json '{"family": "stvk"}' --E 1 --nu 0.3
echo "curve: ok"
