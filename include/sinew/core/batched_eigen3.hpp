#pragma once
// Symmetric 3x3 eigensystems and rotation-variant SVDs of W matrices at once, one per SIMD lane.
// Storage is structure-of-arrays: entry (r, c) of lane l of a 3x3 matrix M is M[r + 3 c][l]
// (column-major, as Eigen and vec() in core/types.hpp). Every step is branch-free over the
// lanes (cyclic Jacobi with exact rotations, selects instead of ifs), so the compiler turns
// each loop over lanes into vector instructions; element kernels put an element's quadrature
// points in the lanes. Same conventions as signed_svd (core/svd.hpp): U and V are rotations,
// sigma is sorted by decreasing magnitude and only sigma_2 may be negative.
#include <algorithm>
#include <cfloat>
#include <cmath>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace sinew::batched {

// Symmetric 3x3 matrices as their six entries: 0 = a00, 1 = a11, 2 = a22, 3 = a01, 4 = a02, 5 = a12.
// Index of the off-diagonal entry (p, q), p != q, among the six.
constexpr int off_diagonal(int p, int q) { return p + q == 1 ? 3 : (p + q == 2 ? 4 : 5); }

#if defined(__AVX512F__)
// 1/sqrt(x) per lane to about an ulp: the 14-bit estimate and two Newton steps, all pipelined,
// where the divider's square root and division are not (on AVX-512 machines they bounded the
// Jacobi sweeps).
inline __m512d rsqrt_pd(__m512d x) {
  const __m512d half_x = _mm512_mul_pd(_mm512_set1_pd(0.5), x), three_halves = _mm512_set1_pd(1.5);
  __m512d y = _mm512_maskz_rsqrt14_pd(0xFF, x);  // (the unmasked form trips -Wuninitialized in GCC 12)
  for (int i = 0; i < 2; ++i) y = _mm512_mul_pd(y, _mm512_fnmadd_pd(half_x, _mm512_mul_pd(y, y), three_halves));
  return y;
}

// One Jacobi rotation zeroing a_pq in 8 lanes starting at lane l0, with r the remaining index.
// With d = a_qq - a_pp, rho = sqrt(d^2 + 4 a_pq^2) and h = |d| + rho: tan = 2 a_pq sgn(d) / h,
// and since h^2 + 4 a_pq^2 = 2 rho h, cos = h / sqrt(2 rho h), sin = 2 a_pq sgn(d) / sqrt(2 rho h),
// tan a_pq = 4 a_pq^2 rho sgn(d) / (2 rho h): two inverse square roots, no division.
template <int W>
[[gnu::always_inline]] inline void jacobi_rotation8(double (&a)[6][W], double (&V)[9][W], int p, int q, int pq, int rp, int rq, int l0) {
  const __m512d apq = _mm512_loadu_pd(&a[pq][l0]), ap = _mm512_loadu_pd(&a[p][l0]), aq = _mm512_loadu_pd(&a[q][l0]);
  const __m512d d = _mm512_sub_pd(aq, ap), zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0);
  const __m512d sign = _mm512_castsi512_pd(
      _mm512_or_si512(_mm512_castpd_si512(one), _mm512_and_si512(_mm512_castpd_si512(d),
                                                                  _mm512_set1_epi64(static_cast<long long>(1ULL << 63)))));
  const __m512d apq2 = _mm512_mul_pd(apq, apq);
  const __m512d x = _mm512_fmadd_pd(_mm512_set1_pd(4.0), apq2, _mm512_mul_pd(d, d));
  const __mmask8 nonzero = _mm512_cmp_pd_mask(x, zero, _CMP_GT_OQ);  // else a_pq = d = 0: no rotation
  const __m512d rho = _mm512_maskz_mul_pd(nonzero, x, rsqrt_pd(x));
  const __m512d h = _mm512_add_pd(_mm512_abs_pd(d), rho);
  const __m512d y = _mm512_mul_pd(_mm512_add_pd(rho, rho), h);
  const __m512d inv = _mm512_maskz_mov_pd(nonzero, rsqrt_pd(y));
  const __m512d c = _mm512_mask_mul_pd(one, nonzero, h, inv);
  const __m512d s = _mm512_mul_pd(_mm512_mul_pd(_mm512_add_pd(apq, apq), sign), inv);
  const __m512d t_apq =
      _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(4.0), apq2), _mm512_mul_pd(rho, sign)), _mm512_mul_pd(inv, inv));
  _mm512_storeu_pd(&a[p][l0], _mm512_sub_pd(ap, t_apq));
  _mm512_storeu_pd(&a[q][l0], _mm512_add_pd(aq, t_apq));
  _mm512_storeu_pd(&a[pq][l0], zero);
  const __m512d arp = _mm512_loadu_pd(&a[rp][l0]), arq = _mm512_loadu_pd(&a[rq][l0]);
  _mm512_storeu_pd(&a[rp][l0], _mm512_fmsub_pd(c, arp, _mm512_mul_pd(s, arq)));
  _mm512_storeu_pd(&a[rq][l0], _mm512_fmadd_pd(s, arp, _mm512_mul_pd(c, arq)));
  for (int i = 0; i < 3; ++i) {
    const __m512d vp = _mm512_loadu_pd(&V[i + 3 * p][l0]), vq = _mm512_loadu_pd(&V[i + 3 * q][l0]);
    _mm512_storeu_pd(&V[i + 3 * p][l0], _mm512_fmsub_pd(c, vp, _mm512_mul_pd(s, vq)));
    _mm512_storeu_pd(&V[i + 3 * q][l0], _mm512_fmadd_pd(s, vp, _mm512_mul_pd(c, vq)));
  }
}
#endif

// Cyclic Jacobi: A <- V^T A V until A is diagonal to rounding; V (3x3 per lane, column-major)
// accumulates the rotations and must hold a rotation on entry (e.g. the identity). At most
// `max_sweeps` sweeps; stops when every lane's off-diagonal part is below 1e-17 of its norm.
// The lanes form W / G groups (e.g. the quadrature points of one element each) that sweep as
// if alone: a group stops when its own lanes have converged, so its result is bitwise what a
// call with its G lanes alone gives, while the groups' division and square-root chains
// overlap in the processor.
template <int W, int G = W>
void jacobi_eigen3(double (&a)[6][W], double (&V)[9][W], int max_sweeps = 8) {
  static_assert(W % G == 0, "groups must tile the lanes");
  constexpr int groups = W / G;
  bool active[groups];
  for (int g = 0; g < groups; ++g) active[g] = true;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    // A lane is unconverged while its off-diagonal part is above 1e-17 of its norm (squared).
    bool unconverged[W];
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const double off = a[3][l] * a[3][l] + a[4][l] * a[4][l] + a[5][l] * a[5][l];
      const double diag = a[0][l] * a[0][l] + a[1][l] * a[1][l] + a[2][l] * a[2][l];
      unconverged[l] = off - 1e-34 * (diag + 2.0 * off) > 0.0;
    }
    bool any = false;
    for (int g = 0; g < groups; ++g) {
      bool u = false;
      for (int l = g * G; l < (g + 1) * G; ++l) u |= unconverged[l];
      active[g] = active[g] && u;
      any |= active[g];
    }
    if (!any) break;
    for (int pair = 0; pair < 3; ++pair) {
      const int p = pair == 2 ? 1 : 0, q = pair == 0 ? 1 : 2, r = 3 - p - q;
      const int pq = off_diagonal(p, q), rp = off_diagonal(r, p), rq = off_diagonal(r, q);
      for (int g = 0; g < groups; ++g) {
        if (!active[g]) continue;
#if defined(__AVX512F__)
        if constexpr (G == 8) {
          jacobi_rotation8<W>(a, V, p, q, pq, rp, rq, g * G);
          continue;
        }
#endif
#pragma omp simd
        for (int l = g * G; l < (g + 1) * G; ++l) {
          const double apq = a[pq][l], d = a[q][l] - a[p][l];
          // t = tan(theta) of the rotation that zeroes a_pq, the smaller root; 0 when a_pq = 0.
          const double t = 2.0 * apq * std::copysign(1.0, d) /
                           (std::abs(d) + std::sqrt(d * d + 4.0 * apq * apq) + DBL_MIN);
          const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
          a[p][l] -= t * apq;
          a[q][l] += t * apq;
          a[pq][l] = 0.0;
          const double arp = a[rp][l], arq = a[rq][l];
          a[rp][l] = c * arp - s * arq;
          a[rq][l] = s * arp + c * arq;
          for (int i = 0; i < 3; ++i) {
            const double vp = V[i + 3 * p][l], vq = V[i + 3 * q][l];
            V[i + 3 * p][l] = c * vp - s * vq;
            V[i + 3 * q][l] = s * vp + c * vq;
          }
        }
      }
    }
  }
}

// Sorts the eigenvalues d (with V's columns) by decreasing value and keeps det V = +1.
template <int W>
void sort_decreasing(double (&d)[3][W], double (&V)[9][W]) {
  constexpr int pairs[3][2] = {{0, 1}, {1, 2}, {0, 1}};
  for (const auto& pq : pairs) {
    const int p = pq[0], q = pq[1];
#pragma omp simd
    for (int l = 0; l < W; ++l) {
      const bool swap = d[q][l] > d[p][l];
      const double dp = d[p][l], dq = d[q][l];
      d[p][l] = swap ? dq : dp;
      d[q][l] = swap ? dp : dq;
      for (int i = 0; i < 3; ++i) {
        const double vp = V[i + 3 * p][l], vq = V[i + 3 * q][l];
        // A swap of two columns flips det V; negating one of them restores it.
        V[i + 3 * p][l] = swap ? vq : vp;
        V[i + 3 * q][l] = swap ? -vp : vq;
      }
    }
  }
}

// Eigensystem of symmetric A (six entries per lane): values decreasing, vectors as the
// columns of the rotation V. A is overwritten. G: lanes per independent group (jacobi_eigen3).
template <int W, int G = W>
void symmetric_eigen3(double (&a)[6][W], double (&values)[3][W], double (&V)[9][W]) {
  for (int i = 0; i < 9; ++i)
    for (int l = 0; l < W; ++l) V[i][l] = (i % 4 == 0) ? 1.0 : 0.0;
  jacobi_eigen3<W, G>(a, V);
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < W; ++l) values[k][l] = a[k][l];
  sort_decreasing<W>(values, V);
}

// Rotation-variant SVD F = U diag(sigma) V^T of each lane's F: V from the eigensystem of
// F^T F, U by orthonormalising F V (twice, so the columns stay orthogonal when F V's second
// column is small), u2 = u0 x u1, and sigma_k = u_k . F v_k, which carries a reflection's sign
// into sigma_2. Rank-deficient F get completed orthonormal frames. G: lanes per independent
// group (jacobi_eigen3).
template <int W, int G = W>
void signed_svd(const double (&F)[9][W], double (&U)[9][W], double (&sigma)[3][W], double (&V)[9][W]) {
  double C[6][W], d[3][W];  // C = F^T F, then its eigenvalues sigma^2 (unused: sigma comes from F v)
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    auto dot = [&](int i, int j) {
      return F[3 * i][l] * F[3 * j][l] + F[3 * i + 1][l] * F[3 * j + 1][l] + F[3 * i + 2][l] * F[3 * j + 2][l];
    };
    C[0][l] = dot(0, 0);
    C[1][l] = dot(1, 1);
    C[2][l] = dot(2, 2);
    C[3][l] = dot(0, 1);
    C[4][l] = dot(0, 2);
    C[5][l] = dot(1, 2);
  }
  symmetric_eigen3<W, G>(C, d, V);
#pragma omp simd
  for (int l = 0; l < W; ++l) {
    double b[3][3];  // b[k] = F v_k
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
        b[k][i] = F[i][l] * V[3 * k][l] + F[i + 3][l] * V[3 * k + 1][l] + F[i + 6][l] * V[3 * k + 2][l];
    const double scale = std::sqrt(C[0][l] + C[1][l] + C[2][l]) + DBL_MIN;  // |F|, C is diagonalised
    // u0: F v0 normalised, e_x when F vanishes.
    double n0 = std::sqrt(b[0][0] * b[0][0] + b[0][1] * b[0][1] + b[0][2] * b[0][2]);
    const bool zero = !(n0 > 1e-300);
    double u0[3] = {zero ? 1.0 : b[0][0] / n0, zero ? 0.0 : b[0][1] / n0, zero ? 0.0 : b[0][2] / n0};
    // u1: F v1 minus its u0 part, twice; a vector orthogonal to u0 when nothing is left.
    double w[3] = {b[1][0], b[1][1], b[1][2]};
    for (int pass = 0; pass < 2; ++pass) {
      const double proj = u0[0] * w[0] + u0[1] * w[1] + u0[2] * w[2];
      for (int i = 0; i < 3; ++i) w[i] -= proj * u0[i];
    }
    double n1 = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    // Fallback: u0 x e_m with e_m the axis least aligned with u0.
    const double ax = std::abs(u0[0]), ay = std::abs(u0[1]), az = std::abs(u0[2]);
    const int m = (ax <= ay && ax <= az) ? 0 : (ay <= az ? 1 : 2);
    double f[3] = {m == 0 ? 0.0 : (m == 1 ? -u0[2] : u0[1]), m == 0 ? u0[2] : (m == 1 ? 0.0 : -u0[0]),
                   m == 0 ? -u0[1] : (m == 1 ? u0[0] : 0.0)};
    const double nf = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    const bool degenerate = !(n1 > 1e-30 * scale);
    for (int i = 0; i < 3; ++i) w[i] = degenerate ? f[i] / nf : w[i] / n1;
    const double u2[3] = {u0[1] * w[2] - u0[2] * w[1], u0[2] * w[0] - u0[0] * w[2], u0[0] * w[1] - u0[1] * w[0]};
    for (int i = 0; i < 3; ++i) {
      U[i][l] = u0[i];
      U[i + 3][l] = w[i];
      U[i + 6][l] = u2[i];
    }
    sigma[0][l] = u0[0] * b[0][0] + u0[1] * b[0][1] + u0[2] * b[0][2];
    sigma[1][l] = w[0] * b[1][0] + w[1] * b[1][1] + w[2] * b[1][2];
    sigma[2][l] = u2[0] * b[2][0] + u2[1] * b[2][1] + u2[2] * b[2][2];
  }
}

}  // namespace sinew::batched
