#include "sinew/forms/element_form.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sinew/core/error.hpp"

namespace sinew {

JacobianKind parse_jacobian_kind(const std::string& text) {
  if (text == "exact") return JacobianKind::Exact;
  if (text == "warped") return JacobianKind::Warped;
  throw Error("unknown constraint Jacobian '" + text + "' (expected exact or warped)", "jacobian");
}

const char* to_string(JacobianKind kind) { return kind == JacobianKind::Exact ? "exact" : "warped"; }

void ElementForm::element_values(const Eigen::VectorXd& x, std::vector<double>& energies) const {
  energies.resize(static_cast<size_t>(discretization().num_elements()));
  // An element costs about a microsecond, less than waking a worker: small meshes stay on one thread.
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, discretization().num_elements(), 128), [&](const auto& range) {
    for (Eigen::Index e = range.begin(); e < range.end(); ++e) energies[static_cast<size_t>(e)] = element_value(e, x);
  });
}

void ElementForm::couplings(std::vector<std::vector<int>>& cliques) const {
  const auto& elements = discretization().mesh().elements;
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    std::vector<int> c(static_cast<size_t>(elements.cols()));
    for (Eigen::Index a = 0; a < elements.cols(); ++a) c[static_cast<size_t>(a)] = elements(e, a);
    cliques.push_back(std::move(c));
  }
}

}  // namespace sinew
