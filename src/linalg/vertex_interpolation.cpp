#include "sinew/linalg/vertex_interpolation.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sinew/core/error.hpp"

namespace sinew {

void VertexInterpolation::prepare() {
  const size_t nc = static_cast<size_t>(coarse_vertices);
  t_offsets.assign(nc + 1, 0);
  for (int c : coarse) ++t_offsets[static_cast<size_t>(c) + 1];
  for (size_t c = 0; c < nc; ++c) t_offsets[c + 1] += t_offsets[c];
  t_fine.resize(coarse.size());
  t_weight.resize(coarse.size());
  std::vector<int> next(t_offsets.begin(), t_offsets.end() - 1);
  for (Eigen::Index v = 0; v < fine_vertices(); ++v)
    for (int k = offsets[static_cast<size_t>(v)]; k < offsets[static_cast<size_t>(v) + 1]; ++k) {
      const int slot = next[static_cast<size_t>(coarse[static_cast<size_t>(k)])]++;
      t_fine[static_cast<size_t>(slot)] = static_cast<int>(v);
      t_weight[static_cast<size_t>(slot)] = weight[static_cast<size_t>(k)];
    }
}

void VertexInterpolation::prolong(const Eigen::VectorXd& coarse_x, std::span<const char> fine_free,
                                  Eigen::VectorXd& fine_x, bool add) const {
  const Eigen::Index nf = fine_vertices();
  if (!add) fine_x.setZero(3 * nf);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, nf, 1024), [&](const auto& range) {
    for (Eigen::Index v = range.begin(); v != range.end(); ++v) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = offsets[static_cast<size_t>(v)]; k < offsets[static_cast<size_t>(v) + 1]; ++k)
        sum += weight[static_cast<size_t>(k)] * coarse_x.segment<3>(3 * coarse[static_cast<size_t>(k)]);
      for (int i = 0; i < 3; ++i)
        if (fine_free[static_cast<size_t>(3 * v + i)]) fine_x[3 * v + i] += sum(i);
    }
  });
}

void VertexInterpolation::restrict_to(const Eigen::VectorXd& fine_x, std::span<const char> fine_free,
                                      Eigen::VectorXd& coarse_x) const {
  if (t_offsets.size() != static_cast<size_t>(coarse_vertices) + 1)
    throw Error("restriction before prepare()", "vertex interpolation");
  coarse_x.resize(3 * coarse_vertices);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, coarse_vertices, 1024), [&](const auto& range) {
    for (Eigen::Index c = range.begin(); c != range.end(); ++c) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = t_offsets[static_cast<size_t>(c)]; k < t_offsets[static_cast<size_t>(c) + 1]; ++k) {
        const Eigen::Index v = t_fine[static_cast<size_t>(k)];
        const double w = t_weight[static_cast<size_t>(k)];
        for (int i = 0; i < 3; ++i)
          if (fine_free[static_cast<size_t>(3 * v + i)]) sum(i) += w * fine_x[3 * v + i];
      }
      coarse_x.segment<3>(3 * c) = sum;
    }
  });
}

std::vector<char> VertexInterpolation::coarse_free(std::span<const char> fine_free) const {
  std::vector<char> free(static_cast<size_t>(3 * coarse_vertices), 0);
  for (Eigen::Index v = 0; v < fine_vertices(); ++v)
    for (int k = offsets[static_cast<size_t>(v)]; k < offsets[static_cast<size_t>(v) + 1]; ++k)
      if (weight[static_cast<size_t>(k)] != 0.0)
        for (int i = 0; i < 3; ++i)
          if (fine_free[static_cast<size_t>(3 * v + i)]) free[static_cast<size_t>(3 * coarse[static_cast<size_t>(k)] + i)] = 1;
  return free;
}

}  // namespace sinew
