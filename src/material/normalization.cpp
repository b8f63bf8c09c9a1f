#include "sinew/material/normalization.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {


namespace {

constexpr int kMaxIterations = 60;
constexpr double kTolerance = 1e-14;  // relative residual (and relative step) of convergence
constexpr double kAccept = 1e-10;     // relative residual a converged answer must reach

Lame lame_of(const MaterialInfo& info, const MaterialParameters& p) {
  return lame_from_energy(*info.make(p));
}

}  // namespace

MaterialParameters normalize(const MaterialInfo& info, const MaterialParameters& base,
                             const Lame& target) {
  const std::string where = fmt::format("material '{}'", info.name);
  if (!std::isfinite(target.lambda) || !std::isfinite(target.mu)) {
    throw Error(fmt::format("target Lame parameters must be finite, got lambda_Lame = {}, "
                            "mu_Lame = {}",
                            target.lambda, target.mu),
                where);
  }
  const double scale = std::max(std::abs(target.lambda), std::abs(target.mu));
  if (scale == 0.0) throw Error("cannot normalise to lambda_Lame = mu_Lame = 0", where);

  MaterialParameters params = complete_parameters(info, base);
  const std::vector<std::string>& keys = info.normalized;
  if (keys.empty()) {
    throw Error(
        "this family has no parameters to normalise (its shape is fixed); use it with "
        "its own parameters or mix it with other families (paper 002 §6)",
        where);
  }
  if (keys.size() > 2) {
    throw Error(fmt::format("{} normalized parameters listed; normalisation solves for one or "
                            "two",
                            keys.size()),
                where);
  }
  for (const auto& key : keys) {
    if (!params.values.count(key)) {
      throw Error(fmt::format("normalized parameter '{}' is not a parameter of the family", key),
                  where);
    }
  }

  // One parameter: lambda_Lame is identically zero (Ogden, ARAP, ... in paper 002 Table 1),
  // so only E can be matched, at nu = 0.
  const int n = static_cast<int>(keys.size());
  if (n == 1 && std::abs(target.lambda) > 1e-12 * scale) {
    const double nu = target.lambda / (2.0 * (target.lambda + target.mu));
    const std::string how =
        info.separable ? fmt::format(", e.g. --mix-mu {} --mix-lambda neo_hookean", info.name) : "";
    throw Error(fmt::format("lambda_Lame is identically 0 for this one-parameter family, so "
                            "it can only match nu = 0 (asked for lambda_Lame = {:.6g}, nu = "
                            "{:.6g}); for nu != 0 mix a volume term in instead (paper 002 §6{})",
                            target.lambda, nu, how),
                where);
  }

  if (info.from_lame) {  // closed form, checked like an iterated answer
    MaterialParameters result = info.from_lame(params, target);
    const Lame l = lame_of(info, result);
    if (!(std::abs(l.lambda - target.lambda) <= kAccept * scale && std::abs(l.mu - target.mu) <= kAccept * scale))
      throw Error(fmt::format("the closed-form parameters give lambda_Lame = {:.6g}, mu_Lame = {:.6g}, not the target "
                              "lambda_Lame = {:.6g}, mu_Lame = {:.6g}",
                              l.lambda, l.mu, target.lambda, target.mu),
                  where);
    return result;
  }

  // x: the unknowns; r(x): the Lamé residual restricted to the matched components.
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (int k = 0; k < n; ++k) x(k) = params.values.at(keys[k]);
  const Eigen::Vector2d x0 = x;
  auto with = [&](const Eigen::Vector2d& y) {
    MaterialParameters p = params;
    for (int k = 0; k < n; ++k) p.values[keys[k]] = y(k);
    return p;
  };
  auto residual = [&](const Eigen::Vector2d& y) -> Eigen::Vector2d {
    const Lame l = lame_of(info, with(y));
    if (n == 1) return {l.mu - target.mu, 0.0};
    return {l.lambda - target.lambda, l.mu - target.mu};
  };

  try {
    Eigen::Vector2d r = residual(x);
    bool converged = false;
    for (int iteration = 0; iteration < kMaxIterations && !converged; ++iteration) {
      if (r.norm() <= kTolerance * scale) {
        converged = true;
        break;
      }
      // Central-difference Jacobian d(Lame)/d(parameters): exact (up to rounding) for an
      // affine map, O(h^2) otherwise.
      // Each parameter is stepped relative to its size, never below its starting size or a
      // thousandth of the largest unknown, so a parameter heading to 0 keeps a usable step.
      Eigen::Matrix2d J = Eigen::Matrix2d::Identity();
      Eigen::Vector2d column_scale = Eigen::Vector2d::Ones();
      for (int k = 0; k < n; ++k) {
        double size = std::max({std::abs(x(k)), std::abs(x0(k)), 1e-3 * x.cwiseAbs().maxCoeff()});
        if (!(size > 0.0)) size = 1.0;
        const double h = 1e-4 * size;
        Eigen::Vector2d xp = x, xm = x;
        xp(k) += h;
        xm(k) -= h;
        J.col(k) = (residual(xp) - residual(xm)) / (2.0 * h);
        column_scale(k) = size;
      }
      // Singular (or numerically singular) when the parameters, measured relative to their
      // size, do not move the Lamé parameters independently.
      Eigen::Vector2d dx = Eigen::Vector2d::Zero();
      bool singular = false;
      if (n == 1) {
        singular = !(std::abs(J(0, 0)) * column_scale(0) > 1e-12 * scale);
        if (!singular) dx(0) = r(0) / J(0, 0);
      } else {
        const Eigen::Matrix2d Js = J * column_scale.asDiagonal();
        const Eigen::JacobiSVD<Eigen::Matrix2d> svd(Js);
        const Eigen::Vector2d sv = svd.singularValues();
        singular = !(sv(1) > 1e-10 * sv(0));
        if (!singular) dx = J.partialPivLu().solve(r);
      }
      if (singular) {
        std::string names;
        for (const auto& key : keys) names += (names.empty() ? "" : ", ") + key;
        throw Error(
            fmt::format("the Jacobian of (lambda_Lame, mu_Lame) with respect to ({}) is "
                        "singular at ({}); these parameters cannot set the Lame "
                        "parameters independently",
                        names,
                        n == 1 ? fmt::format("{}", x(0)) : fmt::format("{}, {}", x(0), x(1))),
            "normalisation");
      }

      // Backtracking keeps nonlinear maps from overshooting; affine maps take full steps.
      double step = 1.0;
      Eigen::Vector2d x_new = x - dx, r_new = residual(x_new);
      for (int halving = 0; halving < 30 && !(r_new.norm() < r.norm()); ++halving) {
        step *= 0.5;
        x_new = x - step * dx;
        r_new = residual(x_new);
      }
      const bool tiny_step =
          (x_new - x).cwiseAbs().maxCoeff() <= kTolerance * x.cwiseAbs().maxCoeff();
      if (r_new.norm() <= r.norm()) {
        x = x_new;
        r = r_new;
      }
      if (tiny_step) converged = true;  // at the rounding floor
    }
    if (!(r.norm() <= kAccept * scale)) {
      throw Error(fmt::format("Newton did not converge in {} iterations (relative residual "
                              "{:.3g})",
                              kMaxIterations, r.norm() / scale),
                  "normalisation");
    }
    MaterialParameters result = with(x);
    if (n == 1) {  // the unmatched lambda_Lame must indeed be zero
      const Lame l = lame_of(info, result);
      if (!(std::abs(l.lambda - target.lambda) <= kAccept * scale)) {
        throw Error(fmt::format("family is listed with one normalized parameter but has "
                                "lambda_Lame = {:.6g} != 0",
                                l.lambda),
                    "normalisation");
      }
    }
    return result;
  } catch (const Error& e) {
    throw e.within(fmt::format("{}: normalising to lambda_Lame = {:.6g}, mu_Lame = {:.6g}", where,
                               target.lambda, target.mu));
  }
}

MaterialParameters normalize(const MaterialInfo& info, const MaterialParameters& base,
                             const YoungPoisson& target) {
  return normalize(info, base, lame_from_young_poisson(target));
}

}  // namespace sinew
