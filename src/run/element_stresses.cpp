#include "sinew/run/element_stresses.hpp"

#include <tbb/parallel_for.h>

#include "sinew/core/error.hpp"

namespace sinew {

ElementStresses element_stresses(const Model& model, const Eigen::VectorXd& x) {
  if (!model.hyperelastic)
    throw Error("stress tensors need a hyperelastic material; the corotational energy-limited model has none",
                "element stresses");
  const Discretization& d = *model.disc;
  const Material& material = model.hyperelastic->material();
  if (x.size() != d.num_dofs()) throw Error("positions do not match the mesh", "element stresses");
  const Eigen::Index m = d.num_elements();
  ElementStresses s;
  s.pk1.resize(m, 9);
  s.cauchy.resize(m, 9);
  using RowMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, m, 256), [&](const auto& r) {
    for (Eigen::Index e = r.begin(); e != r.end(); ++e) {
      const Eigen::Matrix3Xd xe = d.element_positions(e, x);
      Mat3 P = Mat3::Zero(), sigma = Mat3::Zero();
      double volume = 0.0;
      for (int q = 0; q < d.quadrature_points(); ++q) {
        const Mat3 F = xe * d.gradients(e, q);
        const Mat3 Pq = material.pk1(F);
        const double w = d.weight(e, q);
        P += w * Pq;
        sigma += w * Pq * F.transpose() / F.determinant();
        volume += w;
      }
      Eigen::Map<RowMat3>(s.pk1.row(e).data()) = P / volume;
      Eigen::Map<RowMat3>(s.cauchy.row(e).data()) = sigma / volume;
    }
  });
  return s;
}

}  // namespace sinew
