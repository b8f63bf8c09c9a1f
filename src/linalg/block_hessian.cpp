#include "sinew/linalg/block_hessian.hpp"

#include <algorithm>
#include <atomic>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sinew/core/error.hpp"
#include "sinew/linalg/symmetric_product.hpp"

namespace sinew {

BlockHessian::BlockHessian(Eigen::Index num_vertices, const std::vector<std::vector<int>>& cliques)
    : rows_(num_vertices) {
  for (Eigen::Index v = 0; v < num_vertices; ++v) rows_[v].push_back(static_cast<int>(v));
  for (const auto& c : cliques)
    for (int b : c)
      for (int a : c) rows_[b].push_back(a);
  Eigen::Index nnz = 0;
  for (auto& r : rows_) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    nnz += 9 * static_cast<Eigen::Index>(r.size());
  }
  // Fill the compressed column storage directly: column 3b+j holds rows 3a+i, a in rows_[b].
  const Eigen::Index n = 3 * num_vertices;
  A_.resize(n, n);
  A_.resizeNonZeros(nnz);
  auto* outer = A_.outerIndexPtr();
  auto* inner = A_.innerIndexPtr();
  Eigen::Index pos = 0;
  for (Eigen::Index b = 0; b < num_vertices; ++b) {
    for (int j = 0; j < 3; ++j) {
      outer[3 * b + j] = static_cast<int>(pos);
      for (int a : rows_[b])
        for (int i = 0; i < 3; ++i) inner[pos++] = 3 * a + i;
    }
  }
  outer[n] = static_cast<int>(pos);
  set_zero();
  static std::atomic<std::uint64_t> next_id{1};
  pattern_id_ = next_id++;
}

int BlockHessian::max_slots() const {
  size_t m = 0;
  for (const auto& r : rows_) m = std::max(m, r.size());
  return static_cast<int>(m);
}

void BlockHessian::add_symmetric_pair(int a, int b, int k_ab, int k_ba, const Mat3& M) {
  columns(b).add(k_ab, M);
  columns(a).add_transposed(k_ba, M);
}

void BlockHessian::set_zero() {
  // In parallel: at 300k hexahedra the values are ~600 MB (one thread's fill was ~4 % of the
  // Hessian's assembly).
  double* values = A_.valuePtr();
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, A_.nonZeros(), Eigen::Index(1) << 16),
                    [&](const auto& r) { std::fill(values + r.begin(), values + r.end(), 0.0); });
}

int BlockHessian::slot(int a, int b) const {
  const auto& r = rows_[b];
  const auto it = std::lower_bound(r.begin(), r.end(), a);
  return (it != r.end() && *it == a) ? static_cast<int>(it - r.begin()) : -1;
}

void BlockHessian::add_block_at_slot(int b, int k, const Mat3& M) { columns(b).add(k, M); }

void BlockHessian::add_block(int a, int b, const Mat3& M) {
  const int k = slot(a, b);
  if (k < 0) throw Error(fmt::format("block ({}, {}) is not in the Hessian pattern", a, b), "assembly");
  add_block_at_slot(b, k, M);
}

void BlockHessian::set_identity_rows(const std::vector<char>& fixed) {
  double* values = A_.valuePtr();
  const auto* outer = A_.outerIndexPtr();
  const int num_vertices = static_cast<int>(rows_.size());
  for (int v = 0; v < num_vertices; ++v) {
    if (!fixed[3 * v] && !fixed[3 * v + 1] && !fixed[3 * v + 2]) continue;
    // The pattern is symmetric: v's row vertices are the vertices whose columns hold v's rows.
    for (size_t k = 0; k < rows_[v].size(); ++k) {
      const int u = rows_[v][k];
      const int k_vu = slot(v, u);  // v's rows in u's columns
      for (int i = 0; i < 3; ++i) {
        if (!fixed[3 * v + i]) continue;
        for (int j = 0; j < 3; ++j) {
          values[outer[3 * u + j] + 3 * k_vu + i] = 0.0;      // row 3v+i, column 3u+j
          values[outer[3 * v + i] + 3 * static_cast<int>(k) + j] = 0.0;  // column 3v+i, row 3u+j
        }
      }
    }
    const int k_vv = slot(v, v);
    for (int i = 0; i < 3; ++i)
      if (fixed[3 * v + i]) values[outer[3 * v + i] + 3 * k_vv + i] = 1.0;
  }
}

void BlockHessian::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  // (A block-column loop that reads one row index per 3x3 block measured 2.5x slower on a
  // 118k-DOF lattice than this scalar one.)
  symmetric_product(A_, A_.valuePtr(), x, y);
}

Mat3 BlockHessian::diagonal_block(int v) const {
  const Eigen::Index k = block_offset(v, slot(v, v)), stride = column_stride(v);
  const double* values = A_.valuePtr();
  Mat3 M;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) M(i, j) = values[k + i + j * stride];
  return M;
}

void BlockHessian::change_basis(const std::vector<const Mat3*>& frames) {
  double* values = A_.valuePtr();
  const auto* outer = A_.outerIndexPtr();
  for (size_t b = 0; b < rows_.size(); ++b) {
    const Mat3* Qb = frames[b];
    for (size_t k = 0; k < rows_[b].size(); ++k) {
      const Mat3* Qa = frames[rows_[b][k]];
      if (!Qa && !Qb) continue;
      Mat3 M;
      for (int j = 0; j < 3; ++j) M.col(j) = Eigen::Map<const Eigen::Vector3d>(values + outer[3 * b + j] + 3 * k);
      if (Qa) M = Qa->transpose() * M;
      if (Qb) M = M * *Qb;
      for (int j = 0; j < 3; ++j) Eigen::Map<Eigen::Vector3d>(values + outer[3 * b + j] + 3 * k) = M.col(j);
    }
  }
}

}  // namespace sinew
