#include "sinew/forms/element_form.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

JacobianKind parse_jacobian_kind(const std::string& text) {
  if (text == "exact") return JacobianKind::Exact;
  if (text == "warped") return JacobianKind::Warped;
  throw Error("unknown constraint Jacobian '" + text + "' (expected exact or warped)", "jacobian");
}

const char* to_string(JacobianKind kind) { return kind == JacobianKind::Exact ? "exact" : "warped"; }

void ElementForm::couplings(std::vector<std::vector<int>>& cliques) const {
  const auto& elements = discretization().mesh().elements;
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    std::vector<int> c(static_cast<size_t>(elements.cols()));
    for (Eigen::Index a = 0; a < elements.cols(); ++a) c[static_cast<size_t>(a)] = elements(e, a);
    cliques.push_back(std::move(c));
  }
}

}  // namespace sinew
