# `sinew materials`: every family, with Lamé parameters, E and nu from the energy.
source "$(dirname "$0")/common.bash"

expect_ok materials --json
json_check '
fams = d["families"]
assert d["target"] is None
assert len(fams) >= 1
names = [f["name"] for f in fams]
assert len(set(names)) == len(names), "duplicate names"
for f in fams:
    for k in ("name", "title", "reference", "formula", "parameters", "functions", "normalized",
              "separable", "rest_stable", "domain", "lambda_lame", "mu_lame", "E", "nu"):
        assert k in f, (f["name"], k)
    for p in f["parameters"]:
        assert p["value"] == p["default"], (f["name"], p)
    # E and nu are those of the Lame parameters (Eq. 14).
    if f["E"] is not None:
        l, m = f["lambda_lame"], f["mu_lame"]
        assert abs(f["E"] - m * (3 * l + 2 * m) / (l + m)) <= 1e-12 * abs(f["E"]), f["name"]
        assert abs(f["nu"] - l / (2 * (l + m))) <= 1e-12, f["name"]
open(sys.argv[1] + ".names", "w").write("\n".join(names))
'
names=$(cat "$TMP/out.names")
[[ -n $names ]] || fail "no families"
[[ $(grep -c linear_corotational <<<"$names") -eq 1 ]] || fail "linear_corotational missing"

# The text listing names every family too.
expect_ok materials
for n in $names; do grep -q "^$n " "$TMP/out" || fail "text listing lacks $n"; done

# Normalised: two-parameter families hit (E, nu); one-parameter families keep nu = 0 with a
# note; none is an error.
expect_ok materials --json --E 1e5 --nu 0.45
json_check '
assert d["target"] == {"E": 1e5, "nu": 0.45}
for f in d["families"]:
    n = len(f["normalized"])
    if n == 2 and "note" not in f:
        assert abs(f["E"] - 1e5) <= 1e-9 * 1e5, f["name"]
        assert abs(f["nu"] - 0.45) <= 1e-9, f["name"]
    elif n == 1:
        assert "note" in f and "nu = 0" in f["note"], f["name"]
        assert abs(f["E"] - 1e5) <= 1e-9 * 1e5, f["name"]
    elif n == 0:
        assert "note" in f, f["name"]
lc = [f for f in d["families"] if f["name"] == "linear_corotational"][0]
vals = {p["key"]: p["value"] for p in lc["parameters"]}
assert abs(vals["mu"] - 1e5 / 2.9) <= 1e-9 * vals["mu"]
'
expect_ok materials --E 2e3 --nu 0.3
grep -q "normalised to E = 2000, nu = 0.3" "$TMP/out" || fail "text header"

expect_error "--nu" materials --E 1e5
expect_error "--E" materials --nu 0.3
expect_error "--nu" materials --E 1e5 --nu 0.5
expect_error "--E" materials --E -1 --nu 0.3
expect_error "--E" materials --E nan --nu 0.3
echo "materials: ok"
