#pragma once
// Whether a sparse matrix still has the sparsity pattern that symbolic work (an analysis, an
// ordering) was last done for. An operator's pattern id (LinearOperator::pattern_id) answers
// without keeping anything; a matrix without one (id 0) is compared against a kept copy of its
// pattern, as before ids existed.
#include <Eigen/Sparse>
#include <cstdint>
#include <vector>

namespace sinew {

class PatternMemo {
 public:
  // True when A (whose operator reports `id`, 0 for none) has the pattern remembered last;
  // otherwise remembers A's pattern and returns false.
  bool same_or_remember(const Eigen::SparseMatrix<double>& A, std::uint64_t id);
  // Nothing remembered (and no copy kept): the next call answers false.
  void forget();
  // Bytes kept for the comparison (none while ids answer).
  std::size_t bytes() const { return (outer_.capacity() + inner_.capacity()) * sizeof(int); }

 private:
  bool valid_ = false;
  std::uint64_t id_ = 0;
  Eigen::Index rows_ = -1, nnz_ = -1;
  std::vector<int> outer_, inner_;  // only for a pattern without an id
};

}  // namespace sinew
