#include "sinew/assembly/problem.hpp"

#include <algorithm>
#include <limits>

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

void Problem::set_vertex_frames(const std::vector<std::pair<int, Mat3>>& frames) {
  frames_.clear();
  framed_vertices_.clear();
  frame_of_.clear();
  if (frames.empty()) return;
  frames_.reserve(frames.size());
  for (const auto& [v, Q] : frames) {
    if (v < 0 || v >= num_vertices_) throw Error("vertex frame of a vertex outside the mesh", "problem");
    framed_vertices_.push_back(v);
    frames_.push_back(Q);
  }
  frame_of_.assign(num_vertices_, nullptr);
  for (size_t i = 0; i < frames_.size(); ++i) frame_of_[framed_vertices_[i]] = &frames_[i];
}

void Problem::to_global(Eigen::VectorXd& d) const {
  for (size_t i = 0; i < frames_.size(); ++i) {
    auto seg = d.segment<3>(3 * framed_vertices_[i]);
    seg = (frames_[i] * seg).eval();
  }
}

void Problem::to_local(Eigen::VectorXd& g) const {
  for (size_t i = 0; i < frames_.size(); ++i) {
    auto seg = g.segment<3>(3 * framed_vertices_[i]);
    seg = (frames_[i].transpose() * seg).eval();
  }
}

void Problem::set_discretization(std::shared_ptr<const Discretization> discretization) {
  if (discretization && discretization->mesh().num_vertices() != num_vertices_)
    throw Error("the discretisation's vertex count differs from the problem's", "problem");
  discretization_ = std::move(discretization);
}

double Problem::value(const Eigen::VectorXd& x) const {
  if (!is_valid(x)) return std::numeric_limits<double>::infinity();
  double v = 0.0;
  for (const auto& f : forms_) v += f->value(x);
  return v;
}

Eigen::VectorXd Problem::gradient(const Eigen::VectorXd& x) const {
  double unused = 0.0;
  return gradient(x, unused);
}

Eigen::VectorXd Problem::gradient(const Eigen::VectorXd& x, double& force_scale) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(num_dofs());
  Eigen::VectorXd gf(num_dofs());
  force_scale = 0.0;
  for (const auto& f : forms_) {
    gf.setZero();
    f->add_gradient(x, gf);
    force_scale = std::max(force_scale, gf.norm());
    g += gf;
  }
  to_local(g);
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

bool Problem::refresh(const Eigen::VectorXd& x) { return refresh_forms(x, &Form::refresh); }

bool Problem::add_at_iterate(const Eigen::VectorXd& x) { return refresh_forms(x, &Form::add_at_iterate); }

bool Problem::begin_solve(const Eigen::VectorXd& x) { return refresh_forms(x, &Form::begin_solve); }

bool Problem::refresh_forms(const Eigen::VectorXd& x, bool (Form::*hook)(const Eigen::VectorXd&)) {
  bool changed = false;
  bool repattern = false;
  for (const auto& f : forms_) {
    changed = ((*f).*hook)(x) || changed;
    repattern = repattern || f->couplings_changed();
  }
  if (repattern) hessian_.reset();
  return changed;
}

void Problem::set_matrix_free(bool on) {
  if (on == matrix_free_) return;
  matrix_free_ = on;
  hessian_.reset();  // the matrix-free forms leave the pattern
  matrix_free_operator_.reset();
}

std::size_t Problem::hessian_bytes() const {
  std::size_t bytes = 0;
  if (hessian_) {
    const auto& A = hessian_->matrix();
    bytes += static_cast<std::size_t>(A.nonZeros()) * (sizeof(double) + sizeof(int)) +
             static_cast<std::size_t>(A.outerSize() + 1) * sizeof(int);
  }
  if (matrix_free_)
    for (const auto& f : forms_)
      if (f->supports_hessian_product()) bytes += f->hessian_product_bytes();
  return bytes;
}

void Problem::ensure_pattern() {
  if (hessian_) return;
  std::vector<std::vector<int>> cliques;
  for (const auto& f : forms_)
    if (!(matrix_free_ && f->supports_hessian_product())) f->couplings(cliques);
  hessian_ = std::make_unique<BlockHessian>(num_vertices_, cliques);
  hessian_operator_ = std::make_unique<BlockHessianOperator>(*hessian_);
}

const LinearOperator& Problem::hessian(const Eigen::VectorXd& x, bool exact) {
  ensure_pattern();
  hessian_->set_zero();
  for (const auto& f : forms_) f->linearize_at(x);  // non-conservative loads restart their work path here
  std::vector<const Form*> products;
  for (const auto& f : forms_) {
    if (matrix_free_ && f->supports_hessian_product()) {
      f->prepare_hessian_product(x, exact);
      products.push_back(f.get());
    } else if (exact) {
      f->add_exact_hessian(x, *hessian_);
    } else {
      f->add_hessian(x, *hessian_);
    }
  }
  if (matrix_free_) {
    matrix_free_operator_ = std::make_unique<MatrixFreeHessian>(*this, *hessian_, std::move(products));
    return *matrix_free_operator_;
  }
  if (!frame_of_.empty()) hessian_->change_basis(frame_of_);
  hessian_->set_identity_rows(fixed_);  // keeps symmetry and the pattern
  return *hessian_operator_;
}

}  // namespace sinew
