#include "sinew/assembly/matrix_free_hessian.hpp"

#include "sinew/assembly/problem.hpp"

namespace sinew {

class MatrixFreeHessian::Elements final : public ElementMatrices {
 public:
  explicit Elements(const MatrixFreeHessian& H) : H_(&H) {
    for (const Form* f : H.products_) {
      first_.push_back(count_);
      count_ += f->hessian_product_elements();
    }
    first_.push_back(count_);
    const BlockHessian& A = *H.assembled_;
    const int n = static_cast<int>(H.rows() / 3);
    for (int b = 0; b < n; ++b)
      for (const int a : A.column_vertices(b))
        if (a <= b) pairs_.push_back({a, b});
    count_ += static_cast<Eigen::Index>(pairs_.size());
    structure_id_ = A.pattern_id() * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(count_);
  }
  Eigen::Index count() const override { return count_; }
  std::uint64_t structure_id() const override { return structure_id_; }
  int vertices(Eigen::Index e, int* v) const override { return element(e, v, nullptr); }
  void matrix(Eigen::Index e, ElementMatrix& K) const override {
    int v[kMaxElementMatrixVertices];
    const int n = element(e, v, &K);
    const Problem& problem = *H_->problem_;
    for (int a = 0; a < n; ++a)
      if (const Mat3* Q = problem.vertex_frame(v[a])) {
        K.block(3 * a, 0, 3, 3 * n) = Q->transpose() * K.block(3 * a, 0, 3, 3 * n);
        K.block(0, 3 * a, 3 * n, 3) = K.block(0, 3 * a, 3 * n, 3) * *Q;
      }
  }

 private:
  // Element e's vertices and, unless K is null, its matrix (global frame).
  int element(Eigen::Index e, int* v, ElementMatrix* K) const {
    for (size_t f = 0; f + 1 < first_.size(); ++f)
      if (e < first_[f + 1]) return H_->products_[f]->hessian_product_element(e - first_[f], v, K);
    const auto [a, b] = pairs_[static_cast<size_t>(e - first_.back())];
    const BlockHessian& A = *H_->assembled_;
    const auto block = [&](int r, int c) {
      const int k = A.slot(r, c);
      const Eigen::Index offset = A.block_offset(c, k), stride = A.column_stride(c);
      Mat3 M;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) M(i, j) = A.matrix().valuePtr()[offset + i + j * stride];
      return M;
    };
    v[0] = a;
    if (a == b) {
      if (K) K->topLeftCorner<3, 3>() = block(a, a);
      return 1;
    }
    v[1] = b;
    if (K) {
      const Mat3 M = block(a, b);
      K->topLeftCorner<3, 3>().setZero();
      K->block<3, 3>(3, 3).setZero();
      K->block<3, 3>(0, 3) = M;
      K->block<3, 3>(3, 0) = M.transpose();
    }
    return 2;
  }

  const MatrixFreeHessian* H_;
  std::vector<Eigen::Index> first_;  // first element of each product form, then of the assembled blocks
  std::vector<std::pair<int, int>> pairs_;  // assembled blocks (a <= b)
  Eigen::Index count_ = 0;
  std::uint64_t structure_id_ = 0;
};

MatrixFreeHessian::~MatrixFreeHessian() = default;

const ElementMatrices* MatrixFreeHessian::element_matrices() const {
  if (!elements_) elements_ = std::make_unique<Elements>(*this);
  return elements_.get();
}

MatrixFreeHessian::MatrixFreeHessian(const Problem& problem, const BlockHessian& assembled,
                                     std::vector<const Form*> products)
    : problem_(&problem), assembled_(&assembled), products_(std::move(products)) {
  const Eigen::Index vertices = rows() / 3;
  diagonal_.resize(static_cast<size_t>(vertices));
  for (Eigen::Index v = 0; v < vertices; ++v) diagonal_[static_cast<size_t>(v)] = assembled.diagonal_block(static_cast<int>(v));
  for (const Form* f : products_) f->add_hessian_diagonal(diagonal_);
  const std::vector<char>& fixed = problem.fixed();
  for (Eigen::Index v = 0; v < vertices; ++v) {
    Mat3& D = diagonal_[static_cast<size_t>(v)];
    if (const Mat3* Q = problem.vertex_frame(v)) D = Q->transpose() * D * *Q;
    for (int i = 0; i < 3; ++i)
      if (fixed[static_cast<size_t>(3 * v + i)]) {
        D.row(i).setZero();
        D.col(i).setZero();
        D(i, i) = 1.0;
      }
  }
}

void MatrixFreeHessian::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const std::vector<char>& fixed = problem_->fixed();
  // A_local = Q^T A Q with fixed rows and columns replaced by the identity.
  global_ = x;
  for (Eigen::Index i = 0; i < global_.size(); ++i)
    if (fixed[static_cast<size_t>(i)]) global_[i] = 0.0;
  problem_->to_global(global_);
  assembled_->multiply(global_, y);
  for (const Form* f : products_) f->add_hessian_product(global_, y);
  problem_->to_local(y);
  for (Eigen::Index i = 0; i < y.size(); ++i)
    if (fixed[static_cast<size_t>(i)]) y[i] = x[i];
}

}  // namespace sinew
