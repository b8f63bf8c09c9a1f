#include "sinew/linalg/galerkin_product.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

using BlockList = std::vector<std::pair<int, Mat3>, Eigen::aligned_allocator<std::pair<int, Mat3>>>;

// Adds M to the block of vertex b in a short list (linear search: rows have ~27 blocks).
Mat3& block_of(BlockList& list, int b) {
  for (auto& [v, M] : list)
    if (v == b) return M;
  list.emplace_back(b, Mat3::Zero());
  return list.back().second;
}

}  // namespace

std::vector<std::vector<int>> block_pattern(const Eigen::SparseMatrix<double>& A) {
  if (A.rows() % 3 != 0 || A.rows() != A.cols()) throw Error("expects a square matrix of 3x3 blocks", "Galerkin product");
  const Eigen::Index n = A.rows() / 3;
  std::vector<std::vector<int>> pattern(static_cast<size_t>(n));
  tbb::parallel_for(Eigen::Index{0}, n, [&](Eigen::Index a) {
    auto& row = pattern[static_cast<size_t>(a)];
    for (int i = 0; i < 3; ++i)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, 3 * a + i); it; ++it) row.push_back(static_cast<int>(it.row() / 3));
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
  });
  return pattern;
}

std::vector<std::vector<int>> block_pattern(const BlockSparseMatrix& A) {
  std::vector<std::vector<int>> pattern(static_cast<size_t>(A.block_rows()));
  for (int r = 0; r < static_cast<int>(A.block_rows()); ++r)
    for (int k = A.row_begin(r); k < A.row_end(r); ++k) pattern[static_cast<size_t>(r)].push_back(A.column(k));
  return pattern;
}

GalerkinProduct::GalerkinProduct(const std::vector<std::vector<int>>& fine_pattern, const VertexInterpolation& P)
    : P_(&P) {
  const size_t nf = static_cast<size_t>(P.fine_vertices()), nc = static_cast<size_t>(P.coarse_vertices);
  if (fine_pattern.size() != nf) throw Error("the interpolation does not match the matrix", "Galerkin product");
  if (P.t_offsets.size() != nc + 1) throw Error("the interpolation is not prepared", "Galerkin product");
  // Pattern: row I of C holds every J interpolating a vertex b coupled to a vertex a that I
  // interpolates.
  coarse_pattern_.assign(nc, {});
  tbb::parallel_for(size_t{0}, nc, [&](size_t I) {
    auto& row = coarse_pattern_[I];
    for (int k = P.t_offsets[I]; k < P.t_offsets[I + 1]; ++k)
      for (int b : fine_pattern[static_cast<size_t>(P.t_fine[static_cast<size_t>(k)])])
        for (int m = P.offsets[static_cast<size_t>(b)]; m < P.offsets[static_cast<size_t>(b) + 1]; ++m)
          row.push_back(P.coarse[static_cast<size_t>(m)]);
    row.push_back(static_cast<int>(I));  // the diagonal, for coarse DOFs with no free fine DOF
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
  });
  // Greedy colouring: a fine vertex takes the smallest colour not used by a vertex that shares
  // a coarse vertex with it.
  std::vector<int> color(nf, -1);
  std::vector<int> seen;  // colour -> last vertex that marked it
  for (size_t a = 0; a < nf; ++a) {
    for (int k = P.offsets[a]; k < P.offsets[a + 1]; ++k) {
      const size_t I = static_cast<size_t>(P.coarse[static_cast<size_t>(k)]);
      for (int m = P.t_offsets[I]; m < P.t_offsets[I + 1]; ++m) {
        const int c = color[static_cast<size_t>(P.t_fine[static_cast<size_t>(m)])];
        if (c < 0) continue;
        if (static_cast<size_t>(c) >= seen.size()) seen.resize(static_cast<size_t>(c) + 1, -1);
        seen[static_cast<size_t>(c)] = static_cast<int>(a);
      }
    }
    int c = 0;
    while (static_cast<size_t>(c) < seen.size() && seen[static_cast<size_t>(c)] == static_cast<int>(a)) ++c;
    color[a] = c;
    if (static_cast<size_t>(c) >= colors_.size()) colors_.resize(static_cast<size_t>(c) + 1);
    colors_[static_cast<size_t>(c)].push_back(static_cast<int>(a));
  }
}

template <class BlockRow>
void GalerkinProduct::compute_rows(const BlockRow& row, std::span<const char> fine_free, std::span<const char> coarse_free,
                                   BlockSparseMatrix& C) const {
  const VertexInterpolation& P = *P_;
  C.set_zero();
  for (const auto& group : colors_) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, group.size(), 64), [&](const auto& range) {
      BlockList Arow, AProw;
      for (size_t g = range.begin(); g != range.end(); ++g) {
        const int a = group[g];
        const int a0 = P.offsets[static_cast<size_t>(a)], a1 = P.offsets[static_cast<size_t>(a) + 1];
        if (a0 == a1) continue;
        Arow.clear();
        row(a, Arow);
        // (A P)_a = sum_b M_a A_ab M_b w_bJ, with M the free-DOF masks.
        AProw.clear();
        for (auto& [b, B] : Arow) {
          for (int i = 0; i < 3; ++i) {
            if (!fine_free[static_cast<size_t>(3 * a + i)]) B.row(i).setZero();
            if (!fine_free[static_cast<size_t>(3 * b + i)]) B.col(i).setZero();
          }
          for (int m = P.offsets[static_cast<size_t>(b)]; m < P.offsets[static_cast<size_t>(b) + 1]; ++m)
            block_of(AProw, P.coarse[static_cast<size_t>(m)]) += P.weight[static_cast<size_t>(m)] * B;
        }
        for (int k = a0; k < a1; ++k) {
          const int I = P.coarse[static_cast<size_t>(k)];
          const double w = P.weight[static_cast<size_t>(k)];
          for (const auto& [J, B] : AProw) {
            const int slot = C.slot(I, J);
            if (slot < 0) throw Error("the matrix's pattern changed since the symbolic product", "Galerkin product");
            C.block(slot) += w * B;
          }
        }
      }
    });
  }
  // Coarse DOFs without a free fine DOF: identity rows (their rows and columns are zero).
  for (Eigen::Index I = 0; I < C.block_rows(); ++I)
    for (int i = 0; i < 3; ++i)
      if (!coarse_free[static_cast<size_t>(3 * I + i)]) C.block(C.slot(static_cast<int>(I), static_cast<int>(I)))(i, i) = 1.0;
}

void GalerkinProduct::compute(const Eigen::SparseMatrix<double>& A, std::span<const char> fine_free,
                              std::span<const char> coarse_free, BlockSparseMatrix& C) const {
  // Column 3a + i of the symmetric A holds row 3a + i: entry (r, 3a + i) is A_ab(i, r mod 3).
  compute_rows(
      [&](int a, BlockList& out) {
        // Rows are sorted within a column: one forward cursor finds each block, keeping `out` sorted.
        for (int i = 0; i < 3; ++i) {
          size_t pos = 0;
          for (Eigen::SparseMatrix<double>::InnerIterator it(A, 3 * a + i); it; ++it) {
            const int b = static_cast<int>(it.row() / 3);
            while (pos < out.size() && out[pos].first < b) ++pos;
            if (pos == out.size() || out[pos].first != b) out.insert(out.begin() + static_cast<std::ptrdiff_t>(pos), {b, Mat3::Zero()});
            out[pos].second(i, it.row() % 3) = it.value();
          }
        }
      },
      fine_free, coarse_free, C);
}

void GalerkinProduct::compute(const BlockSparseMatrix& A, std::span<const char> fine_free, std::span<const char> coarse_free,
                              BlockSparseMatrix& C) const {
  compute_rows(
      [&](int a, BlockList& out) {
        for (int k = A.row_begin(a); k < A.row_end(a); ++k) out.emplace_back(A.column(k), A.block(k));
      },
      fine_free, coarse_free, C);
}

}  // namespace sinew
