#include "hex_invariant_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "sinew/core/batched_eigen3.hpp"

namespace sinew {
namespace {

constexpr int Q = 8;  // quadrature points, one per lane

bool any_nonzero(const double (&x)[Q]) {
  bool r = false;
  for (int q = 0; q < Q; ++q) r |= x[q] != 0.0;
  return r;
}

// H += s v v^T per lane (v: a 9-vector per lane), upper triangle (n >= m) only.
void add_rank_one(double (&H)[9][9][Q], const double (&s)[Q], const double (&v)[9][Q]) {
  for (int m = 0; m < 9; ++m)
    for (int n = m; n < 9; ++n)
#pragma omp simd
      for (int q = 0; q < Q; ++q) H[m][n][q] += s[q] * v[m][q] * v[n][q];
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

bool add_hex_invariant_stiffness(const InvariantMaterial& material, Projection mode, const HexGradientLanes& D,
                                 const fixed_element::Positions<8>& xe, fixed_element::SymmetricBlocks<8>& K) {
  // F = x_e D per point, column-major: F[i + 3k][q] = sum_a x_ai dN_a/dX_k.
  alignas(64) double F[9][Q] = {};
  for (int a = 0; a < 8; ++a)
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) {
        const double x = xe(i, a);
#pragma omp simd
        for (int q = 0; q < Q; ++q) F[i + 3 * k][q] += x * D.point_lanes[a][k][q];
      }

  // g = vec cof F (columns are cross products of F's columns, paper 000 Eq. 19), I_C, J.
  alignas(64) double G[9][Q], Ic[Q], J[Q];
#pragma omp simd
  for (int q = 0; q < Q; ++q) {
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
  double c_id[Q], c_ff[Q], c_fg[Q], c_gg[Q], c_J[Q];
  const bool positive_j = material.domain() == Domain::PositiveJ;
  for (int q = 0; q < Q; ++q) {
    if (!std::isfinite(Ic[q]) || !std::isfinite(J[q]) || (positive_j && !(J[q] > 0.0))) return false;
    const InvariantMaterial::Derivatives d = material.curvature_derivatives(Ic[q], J[q]);
    c_id[q] = 2.0 * d.dI;
    c_ff[q] = 4.0 * d.dII;
    c_fg[q] = 2.0 * d.dIJ;
    c_gg[q] = d.dJJ;
    c_J[q] = d.dJ;
  }

  // Upper triangle (n >= m) until it is weighted and mirrored below.
  alignas(64) double H[9][9][Q];
  for (int m = 0; m < 9; ++m)
    for (int n = m; n < 9; ++n)
#pragma omp simd
      for (int q = 0; q < Q; ++q)
        H[m][n][q] = c_ff[q] * F[m][q] * F[n][q] + c_fg[q] * (F[m][q] * G[n][q] + G[m][q] * F[n][q]) +
                     c_gg[q] * G[m][q] * G[n][q] + (m == n ? c_id[q] : 0.0);
  // d2J/dF2: block (b, c) of F's columns is s [F_col(x)]_cross (core/svd.cpp volume_hessian).
  constexpr int blocks[6][4] = {{0, 1, 2, -1}, {0, 2, 1, 1}, {1, 0, 2, 1}, {1, 2, 0, -1}, {2, 0, 1, -1}, {2, 1, 0, 1}};
  for (const auto& blk : blocks) {
    if (blk[0] > blk[1]) continue;  // lower blocks: the mirror of the upper ones
    const int r0 = 3 * blk[0], c0 = 3 * blk[1], x = 3 * blk[2];
    const double s = blk[3];
#pragma omp simd
    for (int q = 0; q < Q; ++q) {
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
    alignas(64) double U[9][Q], sigma[3][Q], V[9][Q], shift[Q], v[9][Q];
    batched::signed_svd<Q>(F, U, sigma, V);
    const double r = 1.0 / std::sqrt(2.0);
    // Twist (sign -1) and flip (sign +1) modes of pair k = (i, j): r (u_i v_j^T -+ u_j v_i^T),
    // eigenvalues 2 Psi_I +- Psi_J sigma_k (paper 000 Eq. 35-37, 46-48).
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      for (const double sign : {-1.0, 1.0}) {
        for (int q = 0; q < Q; ++q) shift[q] = projection_shift(mode, floor, c_id[q] - sign * c_J[q] * sigma[k][q]);
        if (!any_nonzero(shift)) continue;
        for (int c = 0; c < 3; ++c)
          for (int row = 0; row < 3; ++row)
#pragma omp simd
            for (int q = 0; q < Q; ++q)
              v[row + 3 * c][q] = r * (U[row + 3 * i][q] * V[c + 3 * j][q] + sign * U[row + 3 * j][q] * V[c + 3 * i][q]);
        add_rank_one(H, shift, v);
      }
    }
    // Scaling modes U diag(w_k) V^T, w_k eigenvectors of the 3x3 block in sigma; only when a
    // lane's block is not above the floor (Sylvester's criterion on block - floor I).
    alignas(64) double A[6][Q], margin[Q];
#pragma omp simd
    for (int q = 0; q < Q; ++q) {
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
    bool above = true;
    for (int q = 0; q < Q; ++q) above &= margin[q] > 0.0;
    if (!above) {
      alignas(64) double values[3][Q], Wv[9][Q];
      batched::symmetric_eigen3<Q>(A, values, Wv);
      for (int k = 0; k < 3; ++k) {
        for (int q = 0; q < Q; ++q) shift[q] = projection_shift(mode, floor, values[k][q]);
        if (!any_nonzero(shift)) continue;
        for (int c = 0; c < 3; ++c)
          for (int row = 0; row < 3; ++row)
#pragma omp simd
            for (int q = 0; q < Q; ++q)
              v[row + 3 * c][q] = U[row][q] * Wv[3 * k][q] * V[c][q] + U[row + 3][q] * Wv[3 * k + 1][q] * V[c + 3][q] +
                                  U[row + 6][q] * Wv[3 * k + 2][q] * V[c + 6][q];
        add_rank_one(H, shift, v);
      }
    }
  }

  for (int m = 0; m < 9; ++m)
    for (int n = m; n < 9; ++n)
#pragma omp simd
      for (int q = 0; q < Q; ++q) {
        H[m][n][q] *= D.weight[q];
        H[n][m][q] = H[m][n][q];
      }

  // B^T H B with the nodes in the lanes: T[q][k][i + 3j][b] = sum_l D_q(b, l) H_q(3k + i, 3l + j),
  // then K_ab(i, j) = sum_q sum_k D_q(a, k) T[q][k][i + 3j][b].
  alignas(64) double T[Q][3][9][8];
  for (int q = 0; q < Q; ++q)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
          const double h0 = H[3 * k + i][j][q], h1 = H[3 * k + i][3 + j][q], h2 = H[3 * k + i][6 + j][q];
#pragma omp simd
          for (int b = 0; b < 8; ++b)
            T[q][k][i + 3 * j][b] = D.node_lanes[q][0][b] * h0 + D.node_lanes[q][1][b] * h1 + D.node_lanes[q][2][b] * h2;
        }
  // Only a <= b is kept: nodes 0-3 of columns b < 4 in 4 lanes, all 8 for the others.
  // The nine entries of a block accumulate side by side: nine independent FMA chains instead
  // of one 24-long chain per entry (that chain's latency bounded the kernel). Same order of
  // summation per entry, so the same rounding.
  const auto column = [&](int b, auto lanes) {
    constexpr int L = decltype(lanes)::value;
    alignas(64) double acc[9][L] = {};
    for (int q = 0; q < Q; ++q)
      for (int k = 0; k < 3; ++k)
        for (int ij = 0; ij < 9; ++ij) {
          const double t = T[q][k][ij][b];
#pragma omp simd
          for (int a = 0; a < L; ++a) acc[ij][a] += D.node_lanes[q][k][a] * t;
        }
    for (int ij = 0; ij < 9; ++ij)
      for (int a = 0; a <= b; ++a) K.K[a][b](ij % 3, ij / 3) += acc[ij][a];
  };
  for (int b = 0; b < 4; ++b) column(b, std::integral_constant<int, 4>());
  for (int b = 4; b < 8; ++b) column(b, std::integral_constant<int, 8>());
  return true;
}

}  // namespace sinew
