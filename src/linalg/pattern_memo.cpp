#include "sinew/linalg/pattern_memo.hpp"

#include <algorithm>

namespace sinew {

bool PatternMemo::same_or_remember(const Eigen::SparseMatrix<double>& A, std::uint64_t id) {
  bool same = false;
  if (valid_ && id != 0)
    same = id == id_;
  else if (valid_ && id_ == 0)
    same = A.isCompressed() && A.rows() == rows_ && A.nonZeros() == nnz_ &&
           outer_.size() == static_cast<std::size_t>(A.outerSize() + 1) &&
           std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1, outer_.begin()) &&
           std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), inner_.begin());
  if (same) return true;
  id_ = id;
  rows_ = A.rows();
  nnz_ = A.nonZeros();
  // An id stands for the pattern, so nothing is kept; an uncompressed matrix (arrays with gaps)
  // is not remembered at all, so that the next call analyses again.
  valid_ = id != 0 || A.isCompressed();
  if (id != 0 || !A.isCompressed()) {
    std::vector<int>().swap(outer_);
    std::vector<int>().swap(inner_);
    return false;
  }
  outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
  inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  return false;
}

void PatternMemo::forget() {
  valid_ = false;
  std::vector<int>().swap(outer_);
  std::vector<int>().swap(inner_);
}

}  // namespace sinew
