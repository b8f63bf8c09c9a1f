#include "sinew/element/element_matrix_cache.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sinew {

void ElementMatrixCache::resize(const Discretization& d) {
  d_ = &d;
  nodes_ = d.nodes();
  blocks_ = nodes_ * (nodes_ + 1) / 2;
  pair_.assign(static_cast<std::size_t>(nodes_ * nodes_), -1);
  int k = 0;
  for (int a = 0; a < nodes_; ++a)
    for (int b = a; b < nodes_; ++b) pair_[static_cast<std::size_t>(a * nodes_ + b)] = k++;
  values_.assign(static_cast<std::size_t>(d.num_elements()) * static_cast<std::size_t>(blocks_) * 9, 0.0f);
}

void ElementMatrixCache::store(Eigen::Index e, int a, int b, const Mat3& K) {
  float* block = values_.data() + (static_cast<std::size_t>(e) * static_cast<std::size_t>(blocks_) + block_index(a, b)) * 9;
  Eigen::Map<Eigen::Matrix3f> target(block);
  target = K.cast<float>();
}

void ElementMatrixCache::add_product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const auto& elements = d_->mesh().elements;
  const int n = nodes_;
  for (const auto& group : d_->color_groups()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, group.size(), 64), [&](const auto& range) {
      // In single precision like the kept blocks (no conversion per block); the element's sum is
      // added to y in double.
      Eigen::Matrix3Xf xe(3, n), ye(3, n);
      for (std::size_t idx = range.begin(); idx != range.end(); ++idx) {
        const Eigen::Index e = group[idx];
        for (int a = 0; a < n; ++a) xe.col(a) = x.segment<3>(3 * elements(e, a)).cast<float>();
        ye.setZero();
        const float* block = values_.data() + static_cast<std::size_t>(e) * static_cast<std::size_t>(blocks_) * 9;
        for (int a = 0; a < n; ++a)
          for (int b = a; b < n; ++b, block += 9) {
            const Eigen::Map<const Eigen::Matrix3f> K(block);
            ye.col(a).noalias() += K * xe.col(b);
            if (b != a) ye.col(b).noalias() += K.transpose() * xe.col(a);
          }
        for (int a = 0; a < n; ++a) y.segment<3>(3 * elements(e, a)) += ye.col(a).cast<double>();
      }
    });
  }
}

void ElementMatrixCache::unpack(Eigen::Index e, Eigen::Ref<Eigen::MatrixXd> K) const {
  const float* block = values_.data() + static_cast<std::size_t>(e) * static_cast<std::size_t>(blocks_) * 9;
  for (int a = 0; a < nodes_; ++a)
    for (int b = a; b < nodes_; ++b, block += 9) {
      const Eigen::Matrix3d M = Eigen::Map<const Eigen::Matrix3f>(block).cast<double>();
      K.block<3, 3>(3 * a, 3 * b) = M;
      if (b != a) K.block<3, 3>(3 * b, 3 * a) = M.transpose();
    }
}

void ElementMatrixCache::add_diagonal(std::vector<Mat3>& diagonal) const {
  const auto& elements = d_->mesh().elements;
  for (const auto& group : d_->color_groups()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, group.size(), 256), [&](const auto& range) {
      for (std::size_t idx = range.begin(); idx != range.end(); ++idx) {
        const Eigen::Index e = group[idx];
        for (int a = 0; a < nodes_; ++a) {
          const float* block = values_.data() + (static_cast<std::size_t>(e) * static_cast<std::size_t>(blocks_) + block_index(a, a)) * 9;
          diagonal[static_cast<std::size_t>(elements(e, a))] += Eigen::Map<const Eigen::Matrix3f>(block).cast<double>();
        }
      }
    });
  }
}

}  // namespace sinew
