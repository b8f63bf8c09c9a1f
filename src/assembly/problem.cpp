#include "sinew/assembly/problem.hpp"

#include <limits>
#include <tbb/parallel_for.h>

#include "sinew/core/error.hpp"

namespace sinew {

Problem::Problem(Eigen::Index num_vertices)
    : num_vertices_(num_vertices), fixed_(3 * num_vertices, 0) {}

void Problem::add_form(std::shared_ptr<Form> form) {
  forms_.push_back(std::move(form));
  hessian_.reset();  // the pattern must include the new form's couplings
}

void Problem::set_fixed(const std::vector<char>& fixed_dofs) {
  if (static_cast<Eigen::Index>(fixed_dofs.size()) != num_dofs())
    throw Error("fixed-DOF mask has the wrong size", "problem");
  fixed_ = fixed_dofs;
}

double Problem::value(const Eigen::VectorXd& x) const {
  if (!is_valid(x)) return std::numeric_limits<double>::infinity();
  double v = 0.0;
  for (const auto& f : forms_) v += f->value(x);
  return v;
}

Eigen::VectorXd Problem::gradient(const Eigen::VectorXd& x) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(num_dofs());
  for (const auto& f : forms_) f->add_gradient(x, g);
  for (Eigen::Index i = 0; i < num_dofs(); ++i)
    if (fixed_[i]) g(i) = 0.0;
  return g;
}

bool Problem::is_valid(const Eigen::VectorXd& x) const {
  if (!x.allFinite()) return false;
  for (const auto& f : forms_)
    if (!f->is_valid(x)) return false;
  return true;
}

bool Problem::refresh(const Eigen::VectorXd& x) { return refresh_forms(x, false); }

bool Problem::begin_solve(const Eigen::VectorXd& x) { return refresh_forms(x, true); }

bool Problem::refresh_forms(const Eigen::VectorXd& x, bool start_of_solve) {
  bool changed = false;
  bool repattern = false;
  for (const auto& f : forms_) {
    changed = (start_of_solve ? f->begin_solve(x) : f->refresh(x)) || changed;
    repattern = repattern || f->couplings_changed();
  }
  if (repattern) hessian_.reset();
  return changed;
}

void Problem::ensure_pattern() {
  if (hessian_) return;
  std::vector<std::vector<int>> cliques;
  for (const auto& f : forms_) f->couplings(cliques);
  hessian_ = std::make_unique<BlockHessian>(num_vertices_, cliques);
  hessian_operator_ = std::make_unique<SparseOperator>(hessian_->matrix());
}

const LinearOperator& Problem::hessian(const Eigen::VectorXd& x) {
  ensure_pattern();
  hessian_->set_zero();
  for (const auto& f : forms_) f->add_hessian(x, *hessian_);
  Eigen::SparseMatrix<double>& A = hessian_->matrix();
  // Identity rows and columns at fixed DOFs (keeps symmetry and the pattern).
  tbb::parallel_for(Eigen::Index(0), A.outerSize(), [&](Eigen::Index c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      if (fixed_[it.row()] || fixed_[it.col()]) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
    }
  });
  return *hessian_operator_;
}

}  // namespace sinew
