#include "sinew/linalg/block_hessian.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

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
}

void BlockHessian::set_zero() {
  std::fill(A_.valuePtr(), A_.valuePtr() + A_.nonZeros(), 0.0);
}

int BlockHessian::slot(int a, int b) const {
  const auto& r = rows_[b];
  const auto it = std::lower_bound(r.begin(), r.end(), a);
  return (it != r.end() && *it == a) ? static_cast<int>(it - r.begin()) : -1;
}

void BlockHessian::add_block_at_slot(int b, int k, const Mat3& M) {
  double* values = A_.valuePtr();
  const auto* outer = A_.outerIndexPtr();
  for (int j = 0; j < 3; ++j) {
    double* col = values + outer[3 * b + j] + 3 * k;
    col[0] += M(0, j);
    col[1] += M(1, j);
    col[2] += M(2, j);
  }
}

void BlockHessian::add_block(int a, int b, const Mat3& M) {
  const int k = slot(a, b);
  if (k < 0) throw Error(fmt::format("block ({}, {}) is not in the Hessian pattern", a, b), "assembly");
  add_block_at_slot(b, k, M);
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
