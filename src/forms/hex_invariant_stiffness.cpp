#include "hex_invariant_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "sinew/core/batched_eigen3.hpp"

namespace sinew {
namespace {

constexpr int Q = 8;  // quadrature points of one element, one per lane

template <int W>
bool any_nonzero(const double (&x)[W]) {
  bool r = false;
  for (int q = 0; q < W; ++q) r |= x[q] != 0.0;
  return r;
}

// H += s v v^T per lane (v: a 9-vector per lane), upper triangle (n >= m) only.
template <int W>
void add_rank_one(double (&H)[9][9][W], const double (&s)[W], const double (&v)[9][W]) {
  for (int m = 0; m < 9; ++m)
    for (int n = m; n < 9; ++n)
#pragma omp simd
      for (int q = 0; q < W; ++q) H[m][n][q] += s[q] * v[m][q] * v[n][q];
}

// Eigenvalue shift of a projection: (projected - original) eigenvalue.
double projection_shift(Projection mode, double floor, double lambda) {
  return mode == Projection::Clamp ? std::max(floor - lambda, 0.0) : std::max(-2.0 * lambda, 0.0);
}

}  // namespace

HexGradientLanes hex_gradient_lanes(const Discretization& d, Eigen::Index e) {
  HexGradientLanes g;
  for (int q = 0; q < Q; ++q) {
    const Eigen::MatrixX3d& D = d.gradients(e, q);
    g.weight[q] = d.weight(e, q);
    for (int a = 0; a < 8; ++a)
      for (int k = 0; k < 3; ++k) {
        g.point_lanes[a][k][q] = D(a, k);
        g.node_lanes[q][k][a] = D(a, k);
      }
  }
  return g;
}

namespace {

// The kernel for E elements at once: their E x 8 quadrature points fill W lanes in the
// point stages (F, the point Hessians, the SVD and the projection), so the Jacobi sweeps'
// division and square-root chains of one element overlap another's; B^T H B runs per element.
// Each element's lanes decide on their own (sweeps, skipped modes), so an element's K is
// bitwise the same whether it comes alone or in a pair.
template <int E>
bool hex_stiffness_kernel(const InvariantMaterial& material, Projection mode, const HexGradientLanes* const (&D)[E],
                          const fixed_element::Positions<8>* const (&xe)[E],
                          fixed_element::SymmetricBlocks<8>* const (&K)[E]) {
  constexpr int W = E * Q;
  // F = x_e D per point, column-major: F[i + 3k][q] = sum_a x_ai dN_a/dX_k.
  alignas(64) double F[9][W] = {};
  for (int el = 0; el < E; ++el)
    for (int a = 0; a < 8; ++a)
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) {
          const double x = (*xe[el])(i, a);
#pragma omp simd
          for (int q = 0; q < Q; ++q) F[i + 3 * k][el * Q + q] += x * D[el]->point_lanes[a][k][q];
        }

  // g = vec cof F (columns are cross products of F's columns, paper 000 Eq. 19), I_C, J.
  alignas(64) double G[9][W], Ic[W], J[W];
#pragma omp simd
  for (int q = 0; q < W; ++q) {
    for (int c = 0; c < 3; ++c) {
      const int c1 = 3 * ((c + 1) % 3), c2 = 3 * ((c + 2) % 3);
      G[3 * c][q] = F[c1 + 1][q] * F[c2 + 2][q] - F[c1 + 2][q] * F[c2 + 1][q];
      G[3 * c + 1][q] = F[c1 + 2][q] * F[c2][q] - F[c1][q] * F[c2 + 2][q];
      G[3 * c + 2][q] = F[c1][q] * F[c2 + 1][q] - F[c1 + 1][q] * F[c2][q];
    }
    J[q] = F[0][q] * G[0][q] + F[1][q] * G[1][q] + F[2][q] * G[2][q];
    double s = 0.0;
    for (int m = 0; m < 9; ++m) s += F[m][q] * F[m][q];
    Ic[q] = s;
  }

  // Invariant derivatives per point: H = c_id I + c_ff f f^T + c_fg (f g^T + g f^T) + c_gg g g^T
  // + c_J d2J/dF2.
  double c_id[W], c_ff[W], c_fg[W], c_gg[W], c_J[W];
  const bool positive_j = material.domain() == Domain::PositiveJ;
  for (int q = 0; q < W; ++q)
    if (!std::isfinite(Ic[q]) || !std::isfinite(J[q]) || (positive_j && !(J[q] > 0.0))) return false;
  InvariantMaterial::Derivatives derivatives[W];
  material.curvature_derivatives_at(W, Ic, J, derivatives);  // one call for all the points
  for (int q = 0; q < W; ++q) {
    const InvariantMaterial::Derivatives& d = derivatives[q];
    c_id[q] = 2.0 * d.dI;
    c_ff[q] = 4.0 * d.dII;
    c_fg[q] = 2.0 * d.dIJ;
    c_gg[q] = d.dJJ;
    c_J[q] = d.dJ;
  }

  // Upper triangle (n >= m) until it is weighted and mirrored below.
  alignas(64) double H[9][9][W];
  for (int m = 0; m < 9; ++m)
    for (int n = m; n < 9; ++n)
#pragma omp simd
      for (int q = 0; q < W; ++q)
        H[m][n][q] = c_ff[q] * F[m][q] * F[n][q] + c_fg[q] * (F[m][q] * G[n][q] + G[m][q] * F[n][q]) +
                     c_gg[q] * G[m][q] * G[n][q] + (m == n ? c_id[q] : 0.0);
  // d2J/dF2: block (b, c) of F's columns is s [F_col(x)]_cross (core/svd.cpp volume_hessian).
  constexpr int blocks[6][4] = {{0, 1, 2, -1}, {0, 2, 1, 1}, {1, 0, 2, 1}, {1, 2, 0, -1}, {2, 0, 1, -1}, {2, 1, 0, 1}};
  for (const auto& blk : blocks) {
    if (blk[0] > blk[1]) continue;  // lower blocks: the mirror of the upper ones
    const int r0 = 3 * blk[0], c0 = 3 * blk[1], x = 3 * blk[2];
    const double s = blk[3];
#pragma omp simd
    for (int q = 0; q < W; ++q) {
      const double v0 = s * c_J[q] * F[x][q], v1 = s * c_J[q] * F[x + 1][q], v2 = s * c_J[q] * F[x + 2][q];
      H[r0][c0 + 1][q] -= v2;
      H[r0][c0 + 2][q] += v1;
      H[r0 + 1][c0][q] += v2;
      H[r0 + 1][c0 + 2][q] -= v0;
      H[r0 + 2][c0][q] -= v1;
      H[r0 + 2][c0 + 1][q] += v0;
    }
  }

  if (mode != Projection::None) {
    const double floor = mode == Projection::Clamp ? material.projection_floor() : 0.0;
    alignas(64) double U[9][W], sigma[3][W], V[9][W], shift[W], v[9][W];
    batched::signed_svd<W, Q>(F, U, sigma, V);
    const double r = 1.0 / std::sqrt(2.0);
    // Twist (sign -1) and flip (sign +1) modes of pair k = (i, j): r (u_i v_j^T -+ u_j v_i^T),
    // eigenvalues 2 Psi_I +- Psi_J sigma_k (paper 000 Eq. 35-37, 46-48). A mode no lane changes
    // is skipped; lanes it does not change add exact zeros.
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      for (const double sign : {-1.0, 1.0}) {
        for (int q = 0; q < W; ++q) shift[q] = projection_shift(mode, floor, c_id[q] - sign * c_J[q] * sigma[k][q]);
        if (!any_nonzero(shift)) continue;
        for (int c = 0; c < 3; ++c)
          for (int row = 0; row < 3; ++row)
#pragma omp simd
            for (int q = 0; q < W; ++q)
              v[row + 3 * c][q] = r * (U[row + 3 * i][q] * V[c + 3 * j][q] + sign * U[row + 3 * j][q] * V[c + 3 * i][q]);
        add_rank_one(H, shift, v);
      }
    }
    // Scaling modes U diag(w_k) V^T, w_k eigenvectors of the 3x3 block in sigma; only for the
    // elements with a lane whose block is not above the floor (Sylvester's criterion on
    // block - floor I).
    alignas(64) double A[6][W], margin[W];
#pragma omp simd
    for (int q = 0; q < W; ++q) {
      const double s0 = sigma[0][q], s1 = sigma[1][q], s2 = sigma[2][q];
      const double g0 = s1 * s2, g1 = s0 * s2, g2 = s0 * s1;
      const double s[3] = {s0, s1, s2}, g[3] = {g0, g1, g2};
      const double hJ[3] = {s2, s1, s0};  // d2J/dsigma_p dsigma_q for (0,1), (0,2), (1,2)
      constexpr int pp[6] = {0, 1, 2, 0, 0, 1}, qq[6] = {0, 1, 2, 1, 2, 2};
      for (int e = 0; e < 6; ++e) {
        const int p = pp[e], t = qq[e];
        A[e][q] = c_ff[q] * s[p] * s[t] + c_fg[q] * (s[p] * g[t] + g[p] * s[t]) + c_gg[q] * g[p] * g[t] +
                  (e < 3 ? c_id[q] : c_J[q] * hJ[e - 3]);
      }
      const double a00 = A[0][q] - floor, a11 = A[1][q] - floor, a22 = A[2][q] - floor;
      const double m2 = a00 * a11 - A[3][q] * A[3][q];
      const double det = a00 * (a11 * a22 - A[5][q] * A[5][q]) - A[3][q] * (A[3][q] * a22 - A[5][q] * A[4][q]) +
                         A[4][q] * (A[3][q] * A[5][q] - a11 * A[4][q]);
      margin[q] = std::min(std::min(a00, m2), det);
    }
    bool above[E], all_above = true;
    for (int el = 0; el < E; ++el) {
      above[el] = true;
      for (int q = el * Q; q < (el + 1) * Q; ++q) above[el] &= margin[q] > 0.0;
      all_above &= above[el];
    }
    if (!all_above) {
      alignas(64) double values[3][W], Wv[9][W];
      batched::symmetric_eigen3<W, Q>(A, values, Wv);
      for (int k = 0; k < 3; ++k) {
        for (int q = 0; q < W; ++q) shift[q] = above[q / Q] ? 0.0 : projection_shift(mode, floor, values[k][q]);
        if (!any_nonzero(shift)) continue;
        for (int c = 0; c < 3; ++c)
          for (int row = 0; row < 3; ++row)
#pragma omp simd
            for (int q = 0; q < W; ++q)
              v[row + 3 * c][q] = U[row][q] * Wv[3 * k][q] * V[c][q] + U[row + 3][q] * Wv[3 * k + 1][q] * V[c + 3][q] +
                                  U[row + 6][q] * Wv[3 * k + 2][q] * V[c + 6][q];
        add_rank_one(H, shift, v);
      }
    }
  }

  for (int el = 0; el < E; ++el)
    for (int m = 0; m < 9; ++m)
      for (int n = m; n < 9; ++n)
#pragma omp simd
        for (int q = 0; q < Q; ++q) {
          H[m][n][el * Q + q] *= D[el]->weight[q];
          H[n][m][el * Q + q] = H[m][n][el * Q + q];
        }

  for (int el = 0; el < E; ++el) {
    const HexGradientLanes& De = *D[el];
    // B^T H B with the nodes in the lanes: T[q][k][i + 3j][b] = sum_l D_q(b, l) H_q(3k + i, 3l + j),
    // then K_ab(i, j) = sum_q sum_k D_q(a, k) T[q][k][i + 3j][b].
    alignas(64) double T[Q][3][9][8];
    for (int q = 0; q < Q; ++q)
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i) {
            const int lane = el * Q + q;
            const double h0 = H[3 * k + i][j][lane], h1 = H[3 * k + i][3 + j][lane], h2 = H[3 * k + i][6 + j][lane];
#pragma omp simd
            for (int b = 0; b < 8; ++b)
              T[q][k][i + 3 * j][b] = De.node_lanes[q][0][b] * h0 + De.node_lanes[q][1][b] * h1 + De.node_lanes[q][2][b] * h2;
          }
    // Only a <= b is kept: nodes 0-3 of columns b < 4 in 4 lanes, all 8 for the others. The
    // nine entries of a block accumulate side by side: nine independent FMA chains instead of
    // one 24-long chain per entry (that chain's latency bounded the kernel).
    fixed_element::SymmetricBlocks<8>& Ke = *K[el];
    const auto column = [&](int b, auto lanes) {
      constexpr int L = decltype(lanes)::value;
      alignas(64) double acc[9][L] = {};
      for (int q = 0; q < Q; ++q)
        for (int k = 0; k < 3; ++k)
          for (int ij = 0; ij < 9; ++ij) {
            const double t = T[q][k][ij][b];
#pragma omp simd
            for (int a = 0; a < L; ++a) acc[ij][a] += De.node_lanes[q][k][a] * t;
          }
      for (int ij = 0; ij < 9; ++ij)
        for (int a = 0; a <= b; ++a) Ke.K[a][b](ij % 3, ij / 3) += acc[ij][a];
    };
    for (int b = 0; b < 4; ++b) column(b, std::integral_constant<int, 4>());
    for (int b = 4; b < 8; ++b) column(b, std::integral_constant<int, 8>());
  }
  return true;
}

}  // namespace

bool add_hex_invariant_stiffness(const InvariantMaterial& material, Projection mode, const HexGradientLanes& D,
                                 const fixed_element::Positions<8>& xe, fixed_element::SymmetricBlocks<8>& K) {
  const HexGradientLanes* d[1] = {&D};
  const fixed_element::Positions<8>* x[1] = {&xe};
  fixed_element::SymmetricBlocks<8>* k[1] = {&K};
  return hex_stiffness_kernel<1>(material, mode, d, x, k);
}

bool add_hex_invariant_stiffness_pair(const InvariantMaterial& material, Projection mode,
                                      const HexGradientLanes& D0, const fixed_element::Positions<8>& x0,
                                      fixed_element::SymmetricBlocks<8>& K0, const HexGradientLanes& D1,
                                      const fixed_element::Positions<8>& x1, fixed_element::SymmetricBlocks<8>& K1) {
  const HexGradientLanes* d[2] = {&D0, &D1};
  const fixed_element::Positions<8>* x[2] = {&x0, &x1};
  fixed_element::SymmetricBlocks<8>* k[2] = {&K0, &K1};
  return hex_stiffness_kernel<2>(material, mode, d, x, k);
}

}  // namespace sinew
