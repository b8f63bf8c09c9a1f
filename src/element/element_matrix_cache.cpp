#include "sinew/element/element_matrix_cache.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <utility>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// Where column node b's panel starts within an element's values: 9 (0 + 1 + ... + b) floats.
constexpr std::size_t panel_offset(int b) { return static_cast<std::size_t>(9 * b * (b + 1) / 2); }

// One element's y_e += K_e x_e for N nodes, panel by panel with sizes known at compile time, so
// each panel product is a short vectorised column loop: the panel of node b adds K_(0..b),b x_b
// to y_0..b, and its off-diagonal blocks' transposes K_(0..b-1),b^T x_0..b-1 to y_b.
template <int N>
void element_product(const float* values, const Eigen::Matrix<float, 3 * N, 1>& xe, Eigen::Matrix<float, 3 * N, 1>& ye) {
  [&]<int... B>(std::integer_sequence<int, B...>) {
    (
        [&] {
          constexpr int R = 3 * (B + 1);
          const Eigen::Map<const Eigen::Matrix<float, R, 3>> P(values + panel_offset(B));
          ye.template head<R>().noalias() += P * xe.template segment<3>(3 * B);
          if constexpr (B > 0)
            ye.template segment<3>(3 * B).noalias() += P.template topRows<3 * B>().transpose() * xe.template head<3 * B>();
        }(),
        ...);
  }(std::make_integer_sequence<int, N>{});
}

template <int N>
void add_product_fixed(const Discretization& d, const std::vector<float>& values, std::size_t per_element,
                       const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const auto& elements = d.mesh().elements;
  // Runs of consecutive elements, coloured so that runs of one colour share no vertex: the kept
  // values stream in order, and a run's x and y entries stay in cache from one element to the
  // next (single elements of one colour are spread over the whole mesh).
  for (const auto& runs : d.run_colors()) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs.size(), 1), [&](const auto& range) {
      // In single precision like the kept values (no conversion per block); the element's sum is
      // added to y in double.
      Eigen::Matrix<float, 3 * N, 1> xe, ye;
      int v[N];
      for (std::size_t run = range.begin(); run != range.end(); ++run)
        for (Eigen::Index e = runs[run].first; e != runs[run].end; ++e) {
          for (int a = 0; a < N; ++a) {
            v[a] = elements(e, a);
            xe.template segment<3>(3 * a) = x.segment<3>(3 * v[a]).template cast<float>();
          }
          ye.setZero();
          element_product<N>(values.data() + static_cast<std::size_t>(e) * per_element, xe, ye);
          for (int a = 0; a < N; ++a) y.segment<3>(3 * v[a]) += ye.template segment<3>(3 * a).template cast<double>();
        }
    });
  }
}

}  // namespace

void ElementMatrixCache::resize(const Discretization& d) {
  if (d.nodes() != 4 && d.nodes() != 8)
    throw Error("kept element matrices support 4- and 8-node elements only", "element matrix cache");
  d_ = &d;
  nodes_ = d.nodes();
  per_element_ = panel_offset(nodes_);
  values_.assign(static_cast<std::size_t>(d.num_elements()) * per_element_, 0.0f);
}

void ElementMatrixCache::store(Eigen::Index e, int a, int b, const Mat3& K) {
  // Column j of block (a, b) is rows 3a..3a+2 of the panel column 3b + j (3 (b + 1) rows).
  float* panel = values_.data() + static_cast<std::size_t>(e) * per_element_ + panel_offset(b);
  const int rows = 3 * (b + 1);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) panel[j * rows + 3 * a + i] = static_cast<float>(K(i, j));
}

Mat3 ElementMatrixCache::block(Eigen::Index e, int a, int b) const {
  const float* panel = values_.data() + static_cast<std::size_t>(e) * per_element_ + panel_offset(b);
  const int rows = 3 * (b + 1);
  Mat3 K;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) K(i, j) = panel[j * rows + 3 * a + i];
  return K;
}

void ElementMatrixCache::add_product(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  if (nodes_ == 8) return add_product_fixed<8>(*d_, values_, per_element_, x, y);
  add_product_fixed<4>(*d_, values_, per_element_, x, y);
}

void ElementMatrixCache::unpack(Eigen::Index e, Eigen::Ref<Eigen::MatrixXd> K) const {
  for (int b = 0; b < nodes_; ++b)
    for (int a = 0; a <= b; ++a) {
      const Mat3 M = block(e, a, b);
      K.block<3, 3>(3 * a, 3 * b) = M;
      if (b != a) K.block<3, 3>(3 * b, 3 * a) = M.transpose();
    }
}

void ElementMatrixCache::add_diagonal(std::vector<Mat3>& diagonal) const {
  const auto& elements = d_->mesh().elements;
  for (const auto& runs : d_->run_colors()) {  // as add_product: runs of consecutive elements
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs.size(), 1), [&](const auto& range) {
      for (std::size_t run = range.begin(); run != range.end(); ++run)
        for (Eigen::Index e = runs[run].first; e != runs[run].end; ++e)
          for (int a = 0; a < nodes_; ++a) diagonal[static_cast<std::size_t>(elements(e, a))] += block(e, a, a);
    });
  }
}

}  // namespace sinew
