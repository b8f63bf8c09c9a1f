#include "sinew/linalg/galerkin_product.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

using BlockList = std::vector<std::pair<int, Mat3>, Eigen::aligned_allocator<std::pair<int, Mat3>>>;

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
    colors_ = std::max(colors_, c + 1);
  }
  // Per coarse vertex I, the interpolation entries (fine vertex a, weight) that reach it, ordered
  // by a's colour: the order in which a scatter over the colours, one after another, would add
  // the rows (A P)_a into row I of C (within a colour at most one a reaches I).
  entry_fine_.resize(P.coarse.size());
  for (size_t a = 0; a < nf; ++a)
    for (int k = P.offsets[a]; k < P.offsets[a + 1]; ++k) entry_fine_[static_cast<size_t>(k)] = static_cast<int>(a);
  gather_offsets_.assign(nc + 1, 0);
  for (const int I : P.coarse) ++gather_offsets_[static_cast<size_t>(I) + 1];
  for (size_t I = 0; I < nc; ++I) gather_offsets_[I + 1] += gather_offsets_[I];
  gather_entries_.resize(P.coarse.size());
  std::vector<int> fill(gather_offsets_.begin(), gather_offsets_.end() - 1);
  for (size_t k = 0; k < P.coarse.size(); ++k) gather_entries_[static_cast<size_t>(fill[static_cast<size_t>(P.coarse[k])]++)] = static_cast<int>(k);
  tbb::parallel_for(size_t{0}, nc, [&](size_t I) {
    std::stable_sort(gather_entries_.begin() + gather_offsets_[I], gather_entries_.begin() + gather_offsets_[I + 1],
                     [&](int k, int m) {
                       return color[static_cast<size_t>(entry_fine_[static_cast<size_t>(k)])] <
                              color[static_cast<size_t>(entry_fine_[static_cast<size_t>(m)])];
                     });
  });
}

template <class BlockRow>
void GalerkinProduct::compute_rows(const BlockRow& row, std::span<const char> fine_free, std::span<const char> coarse_free,
                                   BlockSparseMatrix& C) const {
  const VertexInterpolation& P = *P_;
  // Row by row of C, in parallel over coarse vertices I: row I = sum over the fine vertices a
  // that I interpolates of w_aI (A P)_a, added in colour order (gather_entries_). That is the
  // order of a scatter over colour classes, so C is bitwise what such a scatter gives; but each
  // row of C is written once, by one task, where the scatter swept all of C once per colour
  // (27 passes on a lattice, out of cache on large ones), and the fine rows are read near each
  // other. (A P)_a is needed once per coarse vertex of a (3.4 on average on a lattice).
  //
  // Per thread, indexed by coarse vertex: J's position in the row (A P)_a being formed, and J's
  // slot in row I of C (-1 where unset; each use resets what it set). And the rows (A P)_a formed
  // last (first in, first out), indexed by fine vertex: a task's consecutive coarse rows share
  // fine vertices (the neighbour along the grid's first axis a third of them, the row before
  // along the second most of the rest), so most (A P)_a are formed once or twice, not 3.4 times.
  // Taken from the pool or formed anew, (A P)_a is the same, so C does not depend on it.
  constexpr int pool_size = 2048;
  struct Scratch {
    BlockList Arow;
    std::vector<BlockList> pool;
    std::vector<int> pool_vertex;  // fine vertex of each pool entry (-1: none)
    int next = 0;                  // the entry to replace next
    std::vector<int> position, slot, pooled;
  };
  tbb::enumerable_thread_specific<Scratch> scratch;
  const size_t nc = static_cast<size_t>(P.coarse_vertices), nf = static_cast<size_t>(P.fine_vertices());
  // (A P)_a = sum_b M_a A_ab M_b w_bJ, with M the free-DOF masks.
  const auto form_row = [&](Scratch& s, int a, BlockList& AProw) {
    BlockList& Arow = s.Arow;
    Arow.clear();
    row(a, Arow);
    const bool a_free = fine_free[static_cast<size_t>(3 * a)] && fine_free[static_cast<size_t>(3 * a + 1)] &&
                        fine_free[static_cast<size_t>(3 * a + 2)];
    AProw.clear();
    for (auto& [b, B] : Arow) {
      for (int i = 0; i < 3; ++i) {
        if (!a_free && !fine_free[static_cast<size_t>(3 * a + i)]) B.row(i).setZero();
        if (!fine_free[static_cast<size_t>(3 * b + i)]) B.col(i).setZero();
      }
      for (int m = P.offsets[static_cast<size_t>(b)]; m < P.offsets[static_cast<size_t>(b) + 1]; ++m) {
        const size_t J = static_cast<size_t>(P.coarse[static_cast<size_t>(m)]);
        if (s.position[J] < 0) {
          s.position[J] = static_cast<int>(AProw.size());
          AProw.emplace_back(static_cast<int>(J), Mat3::Zero());
        }
        AProw[static_cast<size_t>(s.position[J])].second += P.weight[static_cast<size_t>(m)] * B;
      }
    }
    for (const auto& entry : AProw) s.position[static_cast<size_t>(entry.first)] = -1;
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nc, 64), [&](const auto& range) {
    Scratch& s = scratch.local();
    if (s.position.size() != nc || s.pooled.size() != nf) {
      s.position.assign(nc, -1);
      s.slot.assign(nc, -1);
      s.pooled.assign(nf, -1);
      s.pool.assign(pool_size, {});
      s.pool_vertex.assign(pool_size, -1);
      s.next = 0;
    }
    for (size_t I = range.begin(); I != range.end(); ++I) {
      const int row_begin = C.row_begin(static_cast<int>(I)), row_end = C.row_end(static_cast<int>(I));
      for (int t = row_begin; t < row_end; ++t) {
        C.block(t).setZero();
        s.slot[static_cast<size_t>(C.column(t))] = t;
      }
      for (int e = gather_offsets_[I]; e < gather_offsets_[I + 1]; ++e) {
        const int k = gather_entries_[static_cast<size_t>(e)];
        const int a = entry_fine_[static_cast<size_t>(k)];
        int entry = s.pooled[static_cast<size_t>(a)];
        if (entry < 0) {
          entry = s.next;
          s.next = (s.next + 1) % pool_size;
          if (s.pool_vertex[static_cast<size_t>(entry)] >= 0)
            s.pooled[static_cast<size_t>(s.pool_vertex[static_cast<size_t>(entry)])] = -1;
          form_row(s, a, s.pool[static_cast<size_t>(entry)]);
          s.pool_vertex[static_cast<size_t>(entry)] = a;
          s.pooled[static_cast<size_t>(a)] = entry;
        }
        const double w = P.weight[static_cast<size_t>(k)];
        for (const auto& [J, B] : s.pool[static_cast<size_t>(entry)]) {
          const int slot = s.slot[static_cast<size_t>(J)];
          if (slot < 0) throw Error("the matrix's pattern changed since the symbolic product", "Galerkin product");
          C.block(slot) += w * B;
        }
      }
      for (int t = row_begin; t < row_end; ++t) s.slot[static_cast<size_t>(C.column(t))] = -1;
      // Coarse DOFs without a free fine DOF: identity rows (their rows and columns are zero).
      const int diagonal = C.slot(static_cast<int>(I), static_cast<int>(I));
      for (int i = 0; i < 3; ++i)
        if (!coarse_free[3 * I + i]) C.block(diagonal)(i, i) = 1.0;
    }
  });
}

void GalerkinProduct::compute(const Eigen::SparseMatrix<double>& A, std::span<const char> fine_free,
                              std::span<const char> coarse_free, BlockSparseMatrix& C) const {
  // Column 3a + i of the symmetric A holds row 3a + i: entry (r, 3a + i) is A_ab(i, r mod 3).
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* values = A.valuePtr();
  compute_rows(
      [&](int a, BlockList& out) {
        // A Newton Hessian's three columns of a vertex list the same full 3x3 blocks: read them
        // block by block.
        const int c0 = outer[3 * a], n0 = outer[3 * a + 1] - c0;
        if (A.isCompressed() && n0 % 3 == 0 && outer[3 * a + 2] - outer[3 * a + 1] == n0 &&
            outer[3 * a + 3] - outer[3 * a + 2] == n0) {
          bool blocks = true;
          for (int k = 0; k < n0 && blocks; k += 3) {
            const int r = inner[c0 + k];
            blocks = r % 3 == 0 && (k == 0 || r > inner[c0 + k - 1]);
            for (int i = 0; i < 3 && blocks; ++i)
              for (int j = 0; j < 3; ++j) blocks = blocks && inner[c0 + i * n0 + k + j] == r + j;
          }
          if (blocks) {
            for (int k = 0; k < n0; k += 3) {
              Mat3 B;
              for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) B(i, j) = values[c0 + i * n0 + k + j];
              out.emplace_back(inner[c0 + k] / 3, B);
            }
            return;
          }
        }
        // Any other pattern: rows are sorted within a column; one forward cursor finds each
        // block, keeping `out` sorted.
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
