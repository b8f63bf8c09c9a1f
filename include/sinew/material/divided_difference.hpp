#pragma once
// Divided differences of one-variable functions, free of cancellation, for the closed-form
// twist/flip eigenvalues of stretch energies (paper 000 Eq. 35-37 generalised):
//   flip quotient  (g(x) - g(y)) / (x - y)  -> g'(x)        as y -> x,
//   twist quotient (g(x) + g(y)) / (x + y)  (singular at y = -x unless g is odd).
namespace sinew::table1 {

// c s^n, and 0 when c = 0 (so a vanishing coefficient never meets 0^negative = inf).
double scaled_power(double c, double s, double n);

// (x^n - y^n) / (x - y), limit n x^(n-1). Integral n (|n| <= 64): an exact polynomial in x, y
// of either sign (x, y != 0 for n < 0). Other n: x, y > 0, via expm1/log1p.
double power_flip(double x, double y, double n);

// (x^n + y^n) / (x + y). Odd integral n: an exact polynomial (no singularity at y = -x).
// Otherwise the plain quotient, with |x + y| kept >= 1e-12 (the quotient is singular there).
double power_twist(double x, double y, double n);

// (log x - log y) / (x - y), limit 1/x; x, y > 0.
double log_flip(double x, double y);

// Generic flip quotient of g from g(x), g(y), g'(x), g'(y): the plain quotient unless x and y
// are closer than the cancellation threshold, then the mean of g' (error O((x - y)^2)).
double flip_quotient(double gx, double gy, double dgx, double dgy, double x, double y);

// Generic twist quotient (g(x) + g(y)) / (x + y), |x + y| kept >= 1e-12. Only for functions
// whose twist is genuinely singular at y = -x, or where x, y > 0.
double twist_quotient(double gx, double gy, double x, double y);

}  // namespace sinew::table1
