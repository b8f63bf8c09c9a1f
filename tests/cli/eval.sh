# `sinew material eval`: JSON keys and shapes, P(I) = 0 for every rest-stable family,
# eigenvalues consistent with the Hessian, projections, mixes.
source "$(dirname "$0")/common.bash"

expect_ok materials --json
"$PY" -c '
import json, sys
d = json.load(open(sys.argv[1]))
for f in d["families"]:
    print(f["name"], int(f["rest_stable"]))
' "$TMP/out" >"$TMP/families"
[[ -s $TMP/families ]] || fail "no families"

I="1 0 0 0 1 0 0 0 1"
F="1.1 0.2 0 -0.1 0.9 0.05 0 0.1 1.2"
while read -r name rest; do
  expect_ok material eval --material "$name" --F $I --json
  json_check '
for k in ("psi", "P", "hessian", "projected_hessian", "eigenvalues", "material", "F", "J"):
    assert k in d, k
assert len(d["P"]) == 3 and all(len(r) == 3 for r in d["P"])
for k in ("hessian", "projected_hessian"):
    assert len(d[k]) == 9 and all(len(r) == 9 for r in d[k]), k
assert len(d["eigenvalues"]) == 9
assert d["projection"] == "clamp"
'
  if [[ $rest == 1 ]]; then
    json_check '
scale = max(1.0, max(abs(x) for r in d["hessian"] for x in r))
assert max(abs(x) for r in d["P"] for x in r) <= 1e-12 * scale, d["P"]
'
  fi
  # A general F: symmetric Hessian, eigenvalues ascending with the Hessian's trace, clamp
  # keeps the non-negative ones (trace of the projection = sum of positive eigenvalues).
  expect_ok material eval --material "$name" --F $F --json
  json_check '
H, Hp, ev = d["hessian"], d["projected_hessian"], d["eigenvalues"]
scale = max(1.0, max(abs(x) for r in H for x in r))
assert all(abs(H[i][j] - H[j][i]) <= 1e-9 * scale for i in range(9) for j in range(9))
assert all(ev[i] <= ev[i + 1] for i in range(8))
assert abs(sum(H[i][i] for i in range(9)) - sum(ev)) <= 1e-9 * scale
assert abs(sum(Hp[i][i] for i in range(9)) - sum(max(e, 0.0) for e in ev)) <= 1e-9 * scale * 9
assert abs(d["J"] - 1.1 * (0.9 * 1.2 - 0.05 * 0.1) + 0.2 * (-0.1 * 1.2)) <= 1e-14
assert d["F"][1] == [-0.1, 0.9, 0.05]
'
done <"$TMP/families"

# Projection none returns the true Hessian; abs has eigenvalue sum |e|.
expect_ok material eval --material linear_corotational --F 0.3 0 0 0 2 0 0 0 -0.5 --projection none --json
json_check 'assert d["projected_hessian"] == d["hessian"]; assert d["projection"] == "none"'
expect_ok material eval --material linear_corotational --F 0.3 0 0 0 2 0 0 0 -0.5 --projection abs --json
json_check '
Hp, ev = d["projected_hessian"], d["eigenvalues"]
assert min(ev) < 0
assert abs(sum(Hp[i][i] for i in range(9)) - sum(abs(e) for e in ev)) <= 1e-9 * sum(abs(e) for e in ev)
'

# Parameters, normalisation, alpha: Lamé from the energy (Eq. 3-4, 15) is unchanged by alpha.
expect_ok material eval --material linear_corotational --param lambda=3 --param mu=0.5 --F $I --json
json_check '
assert d["material"]["lame"] == {"lambda": 3.0, "mu": 0.5}
assert d["material"]["parameters"]["values"] == {"lambda": 3.0, "mu": 0.5}
'
expect_ok material eval --material linear_corotational --E 1e5 --nu 0.3 --alpha 2 --F $F --json
json_check '
m = d["material"]
assert abs(m["E"] - 1e5) <= 1e-9 * 1e5 and abs(m["nu"] - 0.3) <= 1e-12, m
assert m["domain"] == "J > 0" and "alpha=2" in m["name"], m
assert m["spec"]["alpha"] == 2
'

# Mixing (paper 002 Eq. 20).
expect_ok material eval --mix-lambda linear_corotational --mix-mu linear_corotational \
  --alpha-lambda 2 --alpha-mu 0.5 --E 1e4 --nu 0.45 --F $F --json
json_check '
m = d["material"]
lam = 1e4 * 0.45 / (1.45 * 0.1); mu = 1e4 / 2.9
assert abs(m["lame"]["lambda"] - lam) <= 1e-9 * lam and abs(m["lame"]["mu"] - mu) <= 1e-9 * mu, m
assert m["name"].startswith("mix[")
assert m["lambda_part_parameters"]["values"]["lambda"] == 1.0
'

# Text output.
expect_ok material eval --material linear_corotational --F $F
for word in "psi =" "P = dpsi/dF" "Hessian" "projected Hessian (clamp)" "eigenvalues" "lambda_Lame"; do
  grep -qF "$word" "$TMP/out" || fail "text output lacks '$word'"
done
# det F = 1e-200 (issue 13): the formulas overflow; an error naming --F, never NaN with exit 0.
for fmt in "" --json; do
  expect_error "--F (J = 1e-200)" material eval --material neo_hookean --E 1e5 --nu 0.3 \
    --F 1e-200 0 0 0 1 0 0 0 1 $fmt
  grep -qF "not finite" "$TMP/err" || fail "det F = 1e-200: $(cat "$TMP/err")"
done
echo "eval: ok"
