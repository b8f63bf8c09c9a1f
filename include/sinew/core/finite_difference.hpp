#pragma once
// Central finite differences, the one numeric-derivative core of the library: the derivative
// checkers of materials (material/derivative_check.hpp) and energy terms
// (forms/derivative_check.hpp) and every test that differentiates numerically build on these.
// The argument x may be a scalar, a 3x3 matrix or a vector; the function may return a scalar or
// any Eigen object.
#include <Eigen/Core>
#include <type_traits>

namespace sinew {

namespace detail {
template <class T>
auto plain(const T& v) {
  if constexpr (std::is_arithmetic_v<T>) {
    return v;
  } else {
    return v.eval();
  }
}
}  // namespace detail

// (f(x + h d) - f(x - h d)) / 2h: the derivative of f along d, error O(h^2).
template <class Fn, class X, class D>
auto central_difference(const Fn& f, const X& x, const D& d, double h) {
  const X xp = x + h * d;
  const X xm = x - h * d;
  return detail::plain((f(xp) - f(xm)) / (2.0 * h));
}

// One Richardson step on the central difference, (4 D(h/2) - D(h)) / 3: error O(h^4), for
// oracles that must be far more accurate than the tolerance they enforce.
template <class Fn, class X, class D>
auto richardson_difference(const Fn& f, const X& x, const D& d, double h) {
  const auto coarse = central_difference(f, x, d, h);
  const auto fine = central_difference(f, x, d, 0.5 * h);
  return detail::plain((4.0 * fine - coarse) / 3.0);
}

// The mixed second derivative d1^T (d^2 f) d2 of a scalar f by the four-point central formula
// (f(++) - f(+-) - f(-+) + f(--)) / 4h^2; with richardson, one extrapolation step (O(h^4)).
template <class Fn, class X, class D>
double mixed_difference(const Fn& f, const X& x, const D& d1, const D& d2, double h, bool richardson = true) {
  auto at = [&](double hh) {
    const X pp = x + hh * d1 + hh * d2, pm = x + hh * d1 - hh * d2;
    const X mp = x - hh * d1 + hh * d2, mm = x - hh * d1 - hh * d2;
    return (f(pp) - f(pm) - f(mp) + f(mm)) / (4.0 * hh * hh);
  };
  return richardson ? (4.0 * at(0.5 * h) - at(h)) / 3.0 : at(h);
}

// Every partial derivative of a scalar function of a vector (central differences, step h).
template <class Fn>
Eigen::VectorXd difference_gradient(const Fn& f, const Eigen::VectorXd& x, double h, bool richardson = false) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(x.size(), i);
    g(i) = richardson ? richardson_difference(f, x, e, h) : central_difference(f, x, e, h);
  }
  return g;
}

// The Jacobian of a vector function of a vector, column by column (central differences, step h).
template <class Fn>
Eigen::MatrixXd difference_jacobian(const Fn& f, const Eigen::VectorXd& x, double h, bool richardson = false) {
  Eigen::MatrixXd J;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(x.size(), i);
    const Eigen::VectorXd column = richardson ? richardson_difference(f, x, e, h) : central_difference(f, x, e, h);
    if (i == 0) J.resize(column.size(), x.size());
    J.col(i) = column;
  }
  return J;
}

}  // namespace sinew
