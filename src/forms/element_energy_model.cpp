#include "sinew/forms/element_energy_model.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

JacobianKind parse_jacobian_kind(const std::string& text) {
  if (text == "exact") return JacobianKind::Exact;
  if (text == "warped") return JacobianKind::Warped;
  throw Error("unknown constraint Jacobian '" + text + "' (expected exact or warped)", "jacobian");
}

const char* to_string(JacobianKind kind) { return kind == JacobianKind::Exact ? "exact" : "warped"; }

}  // namespace sinew
