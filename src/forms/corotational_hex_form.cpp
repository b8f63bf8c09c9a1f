#include "sinew/forms/corotational_hex_form.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "sinew/core/error.hpp"
#include "sinew/core/svd.hpp"

namespace sinew {
namespace {

// K u for an element stiffness, column by column into a sum the compiler keeps in registers:
// the same sums, in the same order, as Eigen's matrix-vector kernel for K * u, at ~2/3 of its
// time on these 24 x 24 products.
CorotationalHexForm::ElementVector stiffness_times(const CorotationalHexForm::ElementMatrix& K,
                                                  const CorotationalHexForm::ElementVector& u) {
  CorotationalHexForm::ElementVector y;
  const double* k = K.data();
  double* ys = y.data();
  for (int i = 0; i < 24; ++i) ys[i] = k[i] * u(0);
  for (int c = 1; c < 24; ++c) {
    const double uc = u(c);
    const double* column = k + 24 * c;
#pragma GCC unroll 24
    for (int i = 0; i < 24; ++i) ys[i] += column[i] * uc;
  }
  return y;
}

Mat3 tet_edges(const Eigen::Matrix3Xd& xe) {
  Mat3 D;
  for (int k = 0; k < 3; ++k) D.col(k) = xe.col(kInnermostTet[k + 1]) - xe.col(kInnermostTet[0]);
  return D;
}

// The polar decomposition F = R S by Newton's method on the rotation, from a nearby rotation R0
// (the element's rotation at the previous iterate or step): with S_k = R_k^T F and
// R_{k+1} = R_k exp([w]x), the skew part of S vanishes to first order for
// (tr S_k I - sym S_k) w = axial(S_k - S_k^T) (the identity [w]x S + S [w]x = [(tr S I - S) w]x
// for symmetric S). Quadratic convergence: from a rotation a few degrees off, three or four
// iterations reach the rounding level. R is kept as a unit quaternion, so it stays a rotation to
// rounding whatever the number of updates. Returns false (the caller takes the SVD) where F is
// inverted or nearly degenerate, where the iteration does not settle, or where it settled on a
// stationary point of tr(R^T F) other than its maximum (S not positive definite): for det F > 0
// the maximum is the polar factor, U V^T of the rotation-variant SVD, and S = V Sigma V^T.
bool warm_polar(const Mat3& F, const Mat3& R0, Mat3& R, Mat3& S) {
  const double size2 = F.squaredNorm();
  if (!(F.determinant() > 1e-6 * size2 * std::sqrt(size2))) return false;
  Eigen::Quaterniond q(R0);
  q.normalize();
  R = q.toRotationMatrix();
  bool converged = false;
  for (int it = 0; it < 8 && !converged; ++it) {
    S.noalias() = R.transpose() * F;
    const Vec3 a(S(2, 1) - S(1, 2), S(0, 2) - S(2, 0), S(1, 0) - S(0, 1));
    if (a.squaredNorm() <= 1e-30 * size2) {  // symmetric to rounding
      converged = true;
      break;
    }
    const Mat3 sym = 0.5 * (S + S.transpose());
    const Mat3 M = sym.trace() * Mat3::Identity() - sym;
    const Vec3 w = M.inverse() * a;
    const double angle2 = w.squaredNorm();
    if (!(angle2 < 1.0)) return false;  // far from the start, or M singular: the SVD decides
    // exp([w]x) to second order (q' = q (1, w/2), normalised): a retraction, so the convergence
    // stays quadratic, without trigonometry.
    q = q * Eigen::Quaterniond(1.0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z());
    q.normalize();
    R = q.toRotationMatrix();
    if (angle2 <= 1e-26) {  // this update was at the rounding level
      S.noalias() = R.transpose() * F;
      converged = true;
    }
  }
  if (!converged) return false;
  S = 0.5 * (S + S.transpose()).eval();
  // Positive definite (leading minors; det S = det F > 0 already).
  return S(0, 0) > 0.0 && S(0, 0) * S(1, 1) - S(0, 1) * S(1, 0) > 0.0;
}

}  // namespace

HookeCoefficients HookeCoefficients::from_young_poisson(double young, double poisson) {
  const double s = young / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  return {s * (1.0 - poisson), s * poisson, young / (2.0 * (1.0 + poisson))};
}

CorotationalHexForm::CorotationalHexForm(std::shared_ptr<const Discretization> disc, HookeCoefficients coefficients)
    : disc_(std::move(disc)), c_(coefficients) {
  const Discretization& d = *disc_;
  if (d.mesh().kind != ElementKind::Hex8) throw Error("corotational hexahedra need a hexahedral mesh", "corotational");
  const double lambda = c_.E2, mu = c_.E3;
  rest_ = d.mesh().rest_positions();
  const Eigen::VectorXd& X = rest_;
  K_.resize(d.num_elements());
  tet_rest_inverse_.resize(d.num_elements());
  for (Eigen::Index e = 0; e < d.num_elements(); ++e) {
    // K_ab = sum_q w (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I), g = dN/dX (Eq. 10).
    ElementMatrix K = ElementMatrix::Zero();
    for (int q = 0; q < d.quadrature_points(); ++q) {
      const Eigen::MatrixX3d& G = d.gradients(e, q);
      const double w = d.weight(e, q);
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
          const Vec3 ga = G.row(a).transpose(), gb = G.row(b).transpose();
          K.block<3, 3>(3 * a, 3 * b) +=
              w * (lambda * ga * gb.transpose() + mu * gb * ga.transpose() + mu * ga.dot(gb) * Mat3::Identity());
        }
    }
    K_[e] = K;
    tet_rest_inverse_[e] = tet_edges(d.element_positions(e, X)).inverse();
  }
  pair_blocks_.resize(static_cast<size_t>(kNodePairs * 9 * d.num_elements()));
  for (Eigen::Index e = 0; e < d.num_elements(); ++e)
    for (int p = 0; p < kNodePairs; ++p) {
      const auto [a, b] = pair_nodes()[static_cast<size_t>(p)];
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          pair_blocks_[static_cast<size_t>(kNodePairs * (9 * e + 3 * k + l) + p)] = K_[e](3 * a + k, 3 * b + l);
    }
  rotations_ = std::make_unique<ElementRotationCache>(d.num_elements());
}

const std::array<std::array<int, 2>, CorotationalHexForm::kNodePairs>& CorotationalHexForm::pair_nodes() {
  static const auto pairs = [] {
    std::array<std::array<int, 2>, kNodePairs> p{};
    int n = 0;
    for (int b = 0; b < 8; ++b)
      for (int a = 0; a <= b; ++a) p[static_cast<size_t>(n++)] = {a, b};
    return p;
  }();
  return pairs;
}

void CorotationalHexForm::rotated_pair_blocks(Eigen::Index e, const Mat3& R, double* rotated) const {
  // Two 3x3 products per pair, RK = R K_ab and RK R^T, each over all pairs at once. The sums
  // are grouped as Eigen's 3x3 products group them (rows 0 and 1 (p0 + p1) + p2, row 2
  // p0 + (p1 + p2)), so that the blocks are bit for bit those of R * K_ab * R^T.
  constexpr int P = kNodePairs;
  const double* K = pair_blocks_.data() + static_cast<size_t>(P * 9 * e);
  double RK[9 * P];
  for (int i = 0; i < 3; ++i)
    for (int l = 0; l < 3; ++l) {
      const double r0 = R(i, 0), r1 = R(i, 1), r2 = R(i, 2);
      const double* k0 = K + P * l;
      const double* k1 = K + P * (3 + l);
      const double* k2 = K + P * (6 + l);
      double* out = RK + P * (3 * i + l);
      if (i < 2)
        for (int p = 0; p < P; ++p) out[p] = (r0 * k0[p] + r1 * k1[p]) + r2 * k2[p];
      else
        for (int p = 0; p < P; ++p) out[p] = r0 * k0[p] + (r1 * k1[p] + r2 * k2[p]);
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double s0 = R(j, 0), s1 = R(j, 1), s2 = R(j, 2);
      const double* t0 = RK + P * (3 * i);
      const double* t1 = RK + P * (3 * i + 1);
      const double* t2 = RK + P * (3 * i + 2);
      double* out = rotated + P * (3 * i + j);
      if (i < 2)
        for (int p = 0; p < P; ++p) out[p] = (t0[p] * s0 + t1[p] * s1) + t2[p] * s2;
      else
        for (int p = 0; p < P; ++p) out[p] = t0[p] * s0 + (t1[p] * s1 + t2[p] * s2);
    }
}

ElementRotationCache::Corners CorotationalHexForm::corners(Eigen::Index e, const Eigen::VectorXd& x) const {
  const auto& elements = disc_->mesh().elements;
  ElementRotationCache::Corners c;
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i < 3; ++i) c[static_cast<size_t>(3 * k + i)] = x(3 * elements(e, kInnermostTet[k]) + i);
  return c;
}

ElementRotation CorotationalHexForm::compute_rotation(Eigen::Index e, const ElementRotationCache::Corners& c,
                                                      const ElementRotation* warm) const {
  Mat3 D;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) D(i, k) = c[static_cast<size_t>(3 * (k + 1) + i)] - c[static_cast<size_t>(i)];
  const Mat3 F = D * tet_rest_inverse_[e];
  ElementRotation r;
  if (warm && warm_polar(F, warm->R, r.R, r.S)) return r;
  const SignedSvd svd = signed_svd(F);
  r.R = svd.U * svd.V.transpose();
  r.S = svd.V * svd.sigma.asDiagonal() * svd.V.transpose();
  return r;
}

ElementRotation CorotationalHexForm::element_rotation(Eigen::Index e, const Eigen::VectorXd& x) const {
  const ElementRotationCache::Corners c = corners(e, x);
  ElementRotation r;
  bool stale = false;
  if (!rotations_->lookup(e, c, r, &stale)) r = compute_rotation(e, c, stale ? &r : nullptr);
  return r;
}

std::shared_ptr<const std::vector<ElementRotation>> CorotationalHexForm::all_rotations(const Eigen::VectorXd& x) const {
  return rotations_->refresh(
      x, [this](Eigen::Index e, const Eigen::VectorXd& y) { return corners(e, y); },
      [this](Eigen::Index e, const ElementRotationCache::Corners& c, const ElementRotation* warm) {
        return compute_rotation(e, c, warm);
      });
}

double CorotationalHexForm::element_value(Eigen::Index e, const Eigen::VectorXd& x) const {
  return element_value(e, x, element_rotation(e, x).R);
}

CorotationalHexForm::ElementVector CorotationalHexForm::unrotated_displacements(Eigen::Index e, const Eigen::VectorXd& x,
                                                                              const Mat3& R) const {
  // Written out with R's entries in registers (Eigen's segment products took twice as long); the
  // sums are grouped as Eigen groups R^T x_a, ((R_0i x_0 + R_1i x_1) + R_2i x_2), so the values
  // are the same bit for bit.
  const auto& elements = disc_->mesh().elements;
  const double r00 = R(0, 0), r10 = R(1, 0), r20 = R(2, 0);
  const double r01 = R(0, 1), r11 = R(1, 1), r21 = R(2, 1);
  const double r02 = R(0, 2), r12 = R(1, 2), r22 = R(2, 2);
  ElementVector u;
  for (int a = 0; a < 8; ++a) {
    const Eigen::Index v = elements(e, a);
    const double* p = x.data() + 3 * v;
    const double* X = rest_.data() + 3 * v;
    const double p0 = p[0], p1 = p[1], p2 = p[2];
    u(3 * a) = ((r00 * p0 + r10 * p1) + r20 * p2) - X[0];
    u(3 * a + 1) = ((r01 * p0 + r11 * p1) + r21 * p2) - X[1];
    u(3 * a + 2) = ((r02 * p0 + r12 * p1) + r22 * p2) - X[2];
  }
  return u;
}

double CorotationalHexForm::element_value(Eigen::Index e, const Eigen::VectorXd& x, const Mat3& R) const {
  // U_e = sum_q w_q psi(eps_q) with grad u = R^T G - I (Eq. 11) and psi = 1/2 eps : C : eps
  // = 1/2 lambda tr(eps)^2 + mu eps : eps (the E1/E2/E3 terms of Eq. 16) is the quadratic form
  // 1/2 d^T K_e d of the unrotated displacements d = R^T x - X, K_e from the same quadrature
  // (Eq. 10): evaluated so, with fixed-size products.
  // K_e annihilates translations: the mean of d is taken out first, so that a body far from its
  // rest position (metres of fall) does not leave K_e d as a difference of large terms.
  ElementVector u = unrotated_displacements(e, x, R);
  const Vec3 mean = u.reshaped(3, 8).rowwise().mean();
  u.reshaped(3, 8).colwise() -= mean;
  return 0.5 * u.dot(stiffness_times(K_[e], u));
}

void CorotationalHexForm::element_values(const Eigen::VectorXd& x, std::vector<double>& energies) const {
  const auto rotations = all_rotations(x);
  energies.resize(static_cast<size_t>(disc_->num_elements()));
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, disc_->num_elements(), 128), [&](const auto& range) {
    for (Eigen::Index e = range.begin(); e < range.end(); ++e)
      energies[static_cast<size_t>(e)] = element_value(e, x, (*rotations)[static_cast<size_t>(e)].R);
  });
}

// Unrotated displacements d_a = R^T x_a - X_a and rest-frame forces f = K_e d (Eq. 17 with R
// fixed: dU/dx_a = R f_a, exactly the warped elastic force for psi = 1/2 eps : C : eps).
CorotationalHexForm::ElementVector CorotationalHexForm::warped_gradient(const Mat3& R, const ElementVector& f) {
  ElementVector g;
  for (int a = 0; a < 8; ++a) g.segment<3>(3 * a).noalias() = R * f.segment<3>(3 * a);
  return g;
}

Eigen::VectorXd CorotationalHexForm::element_gradient(Eigen::Index e, const Eigen::VectorXd& x,
                                                         JacobianKind kind) const {
  return element_gradient(e, x, kind, element_rotation(e, x));
}

Eigen::VectorXd CorotationalHexForm::element_gradient(Eigen::Index e, const Eigen::VectorXd& x, JacobianKind kind,
                                                         const ElementRotation& rotation) const {
  const Mat3& R = rotation.R;
  const ElementVector disp = unrotated_displacements(e, x, R);
  const ElementVector f = stiffness_times(K_[e], disp);
  Eigen::VectorXd g = warped_gradient(R, f);
  if (kind == JacobianKind::Warped) return g;

  // The rotation's own change (what Eq. 17 discards, Chao et al.): with F_tet = R S and
  // dR = R [omega]x, (tr(S) I - S) omega = axial(R^T dF - dF^T R), and
  // dU = -omega . m with m = sum_a (R^T x_a) x f_a, so dU/dF_tet = -R [n]x, n = (tr S I - S)^-1 m.
  // R^T x_a = d_a + X_a.
  const auto& elements = disc_->mesh().elements;
  Vec3 m = Vec3::Zero();
  for (int a = 0; a < 8; ++a)
    m += (disp.segment<3>(3 * a) + rest_.segment<3>(3 * elements(e, a))).cross(f.segment<3>(3 * a));
  const Mat3& S = rotation.S;
  const Mat3 M = S.trace() * Mat3::Identity() - S;
  const Vec3 n = M.fullPivLu().solve(m);
  const Mat3 dU_dF = -R * cross_matrix(n);
  // F_tet = sum_k (x_{k} - x_0) row_k(Dm^-1): node gradients are dU_dF times rows of Dm^-1.
  const Mat3 GT = dU_dF * tet_rest_inverse_[e].transpose();
  for (int k = 0; k < 3; ++k) {
    g.segment<3>(3 * kInnermostTet[k + 1]) += GT.col(k);
    g.segment<3>(3 * kInnermostTet[0]) -= GT.col(k);
  }
  return g;
}

Eigen::MatrixXd CorotationalHexForm::element_hessian(Eigen::Index e, const Eigen::VectorXd& x) const {
  Eigen::MatrixXd H;
  element_hessian_into(e, x, H);
  return H;
}

void CorotationalHexForm::element_hessian_into(Eigen::Index e, const Eigen::VectorXd& x, Eigen::MatrixXd& He) const {
  // The blocks on and above the diagonal, mirrored below it (K_e is symmetric): the blocks
  // add_hessian assembles.
  double rotated[9 * kNodePairs];
  rotated_pair_blocks(e, element_rotation(e, x).R, rotated);
  He.resize(24, 24);
  for (int p = 0; p < kNodePairs; ++p) {
    const auto [a, b] = pair_nodes()[static_cast<size_t>(p)];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double v = rotated[kNodePairs * (3 * i + j) + p];
        He(3 * a + i, 3 * b + j) = v;
        if (a != b) He(3 * b + j, 3 * a + i) = v;
      }
  }
}

double CorotationalHexForm::value(const Eigen::VectorXd& x) const {
  const auto rotations = all_rotations(x);
  // Deterministic reduction: the same x gives bit-identical energies.
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Eigen::Index>(0, disc_->num_elements(), 64), 0.0,
      [&](const tbb::blocked_range<Eigen::Index>& r, double acc) {
        for (Eigen::Index e = r.begin(); e != r.end(); ++e) acc += element_value(e, x, (*rotations)[static_cast<size_t>(e)].R);
        return acc;
      },
      std::plus<double>());
}

// Element terms are computed in parallel into per-element buffers and scattered serially, so
// the sums are the same whatever the thread count.
void CorotationalHexForm::add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  const Discretization& d = *disc_;
  const auto& elements = d.mesh().elements;
  const auto rotations = all_rotations(x);
  std::vector<ElementVector> ge(static_cast<size_t>(d.num_elements()));
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, d.num_elements(), 32), [&](const auto& range) {
    for (Eigen::Index e = range.begin(); e < range.end(); ++e) {
      // Fixed-size throughout (element_gradient returns a heap vector per element).
      const Mat3& R = (*rotations)[static_cast<size_t>(e)].R;
      ge[static_cast<size_t>(e)] = warped_gradient(R, stiffness_times(K_[e], unrotated_displacements(e, x, R)));
    }
  });
  for (Eigen::Index e = 0; e < d.num_elements(); ++e)
    for (int a = 0; a < 8; ++a) g.segment<3>(3 * elements(e, a)) += ge[static_cast<size_t>(e)].segment<3>(3 * a);
}

const std::vector<int>& CorotationalHexForm::scatter_map(const BlockHessian& H) const {
  const std::lock_guard<std::mutex> lock(scatter_mutex_);
  if (scatter_pattern_ == H.pattern_id() && !scatter_slots_.empty()) return scatter_slots_;
  const auto& elements = disc_->mesh().elements;
  scatter_slots_.resize(static_cast<size_t>(disc_->num_elements()) * 64);
  for (Eigen::Index e = 0; e < disc_->num_elements(); ++e)
    for (int b = 0; b < 8; ++b)
      for (int a = 0; a < 8; ++a) {
        const int k = H.slot(elements(e, a), elements(e, b));
        if (k < 0) throw Error("an element's vertex pair is not in the Hessian pattern", "assembly");
        scatter_slots_[static_cast<size_t>(64 * e + 8 * b + a)] = k;
      }
  scatter_pattern_ = H.pattern_id();
  return scatter_slots_;
}

// Elements of one colour share no vertex, so their blocks are added in parallel.
void CorotationalHexForm::add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const {
  const Discretization& d = *disc_;
  const auto& elements = d.mesh().elements;
  const auto rotations = all_rotations(x);
  const std::vector<int>& slots = scatter_map(H);
  const auto& pairs = pair_nodes();
  for (const auto& group : d.color_groups()) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, group.size(), 16), [&](const auto& r) {
      double rotated[9 * kNodePairs];
      for (size_t idx = r.begin(); idx != r.end(); ++idx) {
        const Eigen::Index e = group[idx];
        // K_e is symmetric (block (b, a) is block (a, b) transposed, bit for bit): the blocks
        // on and above the diagonal are rotated, and added with their transposes below it.
        rotated_pair_blocks(e, (*rotations)[static_cast<size_t>(e)].R, rotated);
        std::array<BlockHessian::Columns, 8> columns;
        for (int a = 0; a < 8; ++a) columns[static_cast<size_t>(a)] = H.columns(elements(e, a));
        const int* element_slots = slots.data() + 64 * e;
        for (int p = 0; p < kNodePairs; ++p) {
          const auto [a, b] = pairs[static_cast<size_t>(p)];
          const BlockHessian::Columns& cb = columns[static_cast<size_t>(b)];
          double* block = cb.values + 3 * element_slots[8 * b + a];
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) block[i + j * cb.stride] += rotated[kNodePairs * (3 * i + j) + p];
          if (a == b) continue;
          const BlockHessian::Columns& ca = columns[static_cast<size_t>(a)];
          double* mirror = ca.values + 3 * element_slots[8 * a + b];
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) mirror[i + j * ca.stride] += rotated[kNodePairs * (3 * j + i) + p];
        }
      }
    });
  }
}

}  // namespace sinew
