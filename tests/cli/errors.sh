# Every user error is one line "sinew: error: <context>: <reason>" on stderr and exit code 2.
source "$(dirname "$0")/common.bash"

I="1 0 0 0 1 0 0 0 1"
EV=(material eval)
M=(--material linear_corotational)

expect_error "--material" "${EV[@]}" --material no_such_family --F $I
expect_error "no_such_family" "${EV[@]}" --material no_such_family --F $I
expect_error "--material" "${EV[@]}" --F $I
expect_error "--param kappa" "${EV[@]}" "${M[@]}" --param kappa=1 --F $I
expect_error "--param" "${EV[@]}" "${M[@]}" --param mu --F $I
expect_error "--param" "${EV[@]}" "${M[@]}" --param =3 --F $I
expect_error "--param mu" "${EV[@]}" "${M[@]}" --param mu=abc --F $I
expect_error "--param mu" "${EV[@]}" "${M[@]}" --param mu=nan --F $I
expect_error "--param mu" "${EV[@]}" "${M[@]}" --param mu=inf --F $I
expect_error "--param mu" "${EV[@]}" "${M[@]}" --param mu=1 --param mu=2 --F $I
expect_error "--fn f" "${EV[@]}" "${M[@]}" --fn f=x --F $I
expect_error "--nu" "${EV[@]}" "${M[@]}" --E 1e5 --nu 0.5 --F $I
expect_error "--nu" "${EV[@]}" "${M[@]}" --E 1e5 --nu 0.7 --F $I
expect_error "--nu" "${EV[@]}" "${M[@]}" --E 1e5 --nu nan --F $I
expect_error "--nu" "${EV[@]}" "${M[@]}" --E 1e5 --F $I
expect_error "--E" "${EV[@]}" "${M[@]}" --E 0 --nu 0.3 --F $I
expect_error "--E" "${EV[@]}" "${M[@]}" --E -5 --nu 0.3 --F $I
expect_error "--E" "${EV[@]}" "${M[@]}" --nu 0.3 --F $I
expect_error "--param mu" "${EV[@]}" "${M[@]}" --E 1e5 --nu 0.3 --param mu=2 --F $I
expect_error "--alpha" "${EV[@]}" "${M[@]}" --alpha 0 --F $I
expect_error "--alpha" "${EV[@]}" "${M[@]}" --alpha -1 --F $I
expect_error "--alpha" "${EV[@]}" "${M[@]}" --alpha nan --F $I
expect_error "--F" "${EV[@]}" "${M[@]}" --F 1 0 0 0 1 0 0 0
expect_error "--F" "${EV[@]}" "${M[@]}" --F 1 0 0 0 1 0 0 0 1 1
expect_error "--F" "${EV[@]}" "${M[@]}"
expect_error "--F entry f12" "${EV[@]}" "${M[@]}" --F 1 0 0 0 1 nan 0 0 1
expect_error "--F entry f00" "${EV[@]}" "${M[@]}" --F x 0 0 0 1 0 0 0 1
# Outside the domain: alpha != 1 needs J > 0.
expect_error "--F" "${EV[@]}" "${M[@]}" --alpha 2 --F 1 0 0 0 1 0 0 0 -1
expect_error "J = det F > 0" "${EV[@]}" "${M[@]}" --alpha 2 --F 1 0 0 0 1 0 0 0 -1
expect_error "--projection" "${EV[@]}" "${M[@]}" --projection round --F $I
# Mixing.
expect_error "--mix-mu" "${EV[@]}" --mix-lambda linear_corotational --E 1 --nu 0.3 --F $I
expect_error "--mix-lambda" "${EV[@]}" --mix-mu linear_corotational --E 1 --nu 0.3 --F $I
expect_error "--E" "${EV[@]}" --mix-lambda linear_corotational --mix-mu linear_corotational --F $I
expect_error "--mix-mu" "${EV[@]}" --mix-lambda linear_corotational --mix-mu nope --E 1 --nu 0.3 --F $I
expect_error "--alpha-mu" "${EV[@]}" --mix-lambda linear_corotational --mix-mu linear_corotational --E 1 --nu 0.3 --alpha-mu 0 --F $I
expect_error "--alpha" "${EV[@]}" --mix-lambda linear_corotational --mix-mu linear_corotational --E 1 --nu 0.3 --alpha 2 --F $I
expect_error "--material" "${EV[@]}" "${M[@]}" --mix-lambda linear_corotational --mix-mu linear_corotational --E 1 --nu 0.3 --F $I
expect_error "--alpha-lambda" "${EV[@]}" "${M[@]}" --alpha-lambda 2 --F $I
# Curves.
CU=(material curve "${M[@]}")
expect_error "--steps" "${CU[@]}" --steps 0
expect_error "--steps" "${CU[@]}" --steps 2.5
expect_error "--steps" "${CU[@]}" --steps -3
expect_error "--stretch-from" "${CU[@]}" --stretch-from 2 --stretch-to 1
expect_error "--stretch-from" "${CU[@]}" --stretch-from 1 --stretch-to 1
expect_error "--stretch-from" "${CU[@]}" --stretch-from 0 --stretch-to 1
expect_error "--stretch-from" "${CU[@]}" --stretch-from nan
expect_error "--stretch-to" "${CU[@]}" --stretch-to inf
expect_error "--mode" "${CU[@]}" --mode torsion
expect_error "no lateral stretch" "${CU[@]}" --stretch-from 1 --stretch-to 6 --steps 5
# Command-line syntax.
expect_error "--bogus" "${EV[@]}" "${M[@]}" --F $I --bogus
expect_error "--E" "${EV[@]}" "${M[@]}" --F $I --E
echo "errors: ok"
