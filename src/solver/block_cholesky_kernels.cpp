#include "block_cholesky_kernels.hpp"

#include <cmath>

namespace sinew::block_kernels {
namespace {

// The Cholesky factor of a symmetric 3x3 block (its lower triangle read) and the factor's
// inverse, both lower triangular and padded; false unless positive definite.
bool llt3(const double* a, double* L, double* inverse) {
  const double d0 = a[0];
  if (!(d0 > 0.0)) return false;
  const double l00 = std::sqrt(d0), l10 = a[1] / l00, l20 = a[2] / l00;
  const double d1 = a[5] - l10 * l10;
  if (!(d1 > 0.0)) return false;
  const double l11 = std::sqrt(d1), l21 = (a[6] - l20 * l10) / l11;
  const double d2 = a[10] - l20 * l20 - l21 * l21;
  if (!(d2 > 0.0)) return false;
  const double l22 = std::sqrt(d2);
  const double i00 = 1.0 / l00, i11 = 1.0 / l11, i22 = 1.0 / l22;
  const double i10 = -l10 * i00 * i11, i21 = -l21 * i11 * i22, i20 = -(l20 * i00 + l21 * i10) * i22;
  for (int k = 0; k < kBlock; ++k) L[k] = inverse[k] = 0.0;
  L[0] = l00, L[1] = l10, L[2] = l20, L[5] = l11, L[6] = l21, L[10] = l22;
  inverse[0] = i00, inverse[1] = i10, inverse[2] = i20, inverse[5] = i11, inverse[6] = i21, inverse[10] = i22;
  return true;
}

}  // namespace

bool factorize(int nv, const int* start, const int* rows, double* blocks, double* diagonal_inverse, int* work) {
  // Left-looking: column j gets the updates of every earlier column k with a block in row j
  // (k waits in the list of the row of its next unused block), then its own factor.
  int* head = work;
  int* next = work + nv;
  int* cursor = work + 2 * nv;
  int* position = work + 3 * nv;
  for (int j = 0; j < nv; ++j) head[j] = -1;
  auto enqueue = [&](int k) {
    const int row = rows[cursor[k]];
    next[k] = head[row];
    head[row] = k;
  };
  for (int j = 0; j < nv; ++j) {
    const int begin = start[j], end = start[j + 1];
    for (int p = begin; p < end; ++p) position[rows[p]] = p;
    for (int k = head[j]; k != -1;) {
      const int k_next = next[k];
      const int p = cursor[k], k_end = start[k + 1];
      // L(rows[q], j) -= L(rows[q], k) L(j, k)^T for the blocks q of column k from row j down:
      // column c of the product is sum_l L_q.col(l) L_jk(c, l).
      const double* Ljk = blocks + kBlock * p;
      const double b00 = Ljk[0], b01 = Ljk[4], b02 = Ljk[8];
      const double b10 = Ljk[1], b11 = Ljk[5], b12 = Ljk[9];
      const double b20 = Ljk[2], b21 = Ljk[6], b22 = Ljk[10];
      for (int q = p; q < k_end; ++q) {
        const double* __restrict X = blocks + kBlock * q;
        double* __restrict T = blocks + kBlock * position[rows[q]];
#pragma omp simd
        for (int r = 0; r < 4; ++r) {
          const double x0 = X[r], x1 = X[4 + r], x2 = X[8 + r];
          T[r] -= x0 * b00 + x1 * b01 + x2 * b02;
          T[4 + r] -= x0 * b10 + x1 * b11 + x2 * b12;
          T[8 + r] -= x0 * b20 + x1 * b21 + x2 * b22;
        }
      }
      if (p + 1 < k_end) {
        cursor[k] = p + 1;
        enqueue(k);
      }
      k = k_next;
    }
    double* D = blocks + kBlock * begin;
    double* I = diagonal_inverse + kBlock * j;
    double a[kBlock];
    for (int k = 0; k < kBlock; ++k) a[k] = D[k];
    if (!llt3(a, D, I)) return false;
    // L(rows[p], j) = A(rows[p], j) L_jj^-T: column c is sum_{l <= c} X.col(l) I(c, l).
    const double i00 = I[0], i10 = I[1], i20 = I[2], i11 = I[5], i21 = I[6], i22 = I[10];
    for (int p = begin + 1; p < end; ++p) {
      double* __restrict X = blocks + kBlock * p;
#pragma omp simd
      for (int r = 0; r < 4; ++r) {
        const double x0 = X[r], x1 = X[4 + r], x2 = X[8 + r];
        X[r] = x0 * i00;
        X[4 + r] = x0 * i10 + x1 * i11;
        X[8 + r] = x0 * i20 + x1 * i21 + x2 * i22;
      }
    }
    if (begin + 1 < end) {
      cursor[j] = begin + 1;
      enqueue(j);
    }
  }
  return true;
}

void forward(int nv, const int* start, const int* rows, const double* blocks, const double* diagonal_inverse, double* y,
             int first) {
  for (int j = first; j < nv; ++j) {
    double* yj = y + 4 * j;
    if (yj[0] == 0.0 && yj[1] == 0.0 && yj[2] == 0.0) continue;  // sparse right-hand sides: nothing to carry down
    const double* I = diagonal_inverse + kBlock * j;
    const double z0 = I[0] * yj[0];
    const double z1 = I[1] * yj[0] + I[5] * yj[1];
    const double z2 = I[2] * yj[0] + I[6] * yj[1] + I[10] * yj[2];
    yj[0] = z0, yj[1] = z1, yj[2] = z2;
    for (int p = start[j] + 1; p < start[j + 1]; ++p) {
      const double* __restrict X = blocks + kBlock * p;
      double* __restrict t = y + 4 * rows[p];
#pragma omp simd
      for (int r = 0; r < 4; ++r) t[r] -= X[r] * z0 + X[4 + r] * z1 + X[8 + r] * z2;
    }
  }
}

void backward(int nv, const int* start, const int* rows, const double* blocks, const double* diagonal_inverse, double* y) {
  for (int j = nv - 1; j >= 0; --j) {
    // s = y_j - sum_p L_p^T y_rows[p]: per column of L_p a 4-wide product, summed at the end.
    double a0[4] = {}, a1[4] = {}, a2[4] = {};
    for (int p = start[j] + 1; p < start[j + 1]; ++p) {
      const double* __restrict X = blocks + kBlock * p;
      const double* __restrict t = y + 4 * rows[p];
#pragma omp simd
      for (int r = 0; r < 4; ++r) {
        a0[r] += X[r] * t[r];
        a1[r] += X[4 + r] * t[r];
        a2[r] += X[8 + r] * t[r];
      }
    }
    double* yj = y + 4 * j;
    const double s0 = yj[0] - ((a0[0] + a0[1]) + (a0[2] + a0[3]));
    const double s1 = yj[1] - ((a1[0] + a1[1]) + (a1[2] + a1[3]));
    const double s2 = yj[2] - ((a2[0] + a2[1]) + (a2[2] + a2[3]));
    // y_j = L_jj^-T s.
    const double* I = diagonal_inverse + kBlock * j;
    yj[0] = I[0] * s0 + I[1] * s1 + I[2] * s2;
    yj[1] = I[5] * s1 + I[6] * s2;
    yj[2] = I[10] * s2;
  }
}

void forward_many(int nv, const int* start, const int* rows, const double* blocks, const double* diagonal_inverse,
                  double* Y, int ld, int m) {
  for (int j = 0; j < nv; ++j) {
    double* __restrict y0 = Y + static_cast<long>(3 * j) * ld;
    double* __restrict y1 = y0 + ld;
    double* __restrict y2 = y1 + ld;
    bool zero = true;
    for (int c = 0; c < m && zero; ++c) zero = y0[c] == 0.0 && y1[c] == 0.0 && y2[c] == 0.0;
    if (zero) continue;
    const double* I = diagonal_inverse + kBlock * j;
    const double i00 = I[0], i10 = I[1], i20 = I[2], i11 = I[5], i21 = I[6], i22 = I[10];
#pragma omp simd
    for (int c = 0; c < m; ++c) {
      const double a = y0[c], b = y1[c], d = y2[c];
      y0[c] = i00 * a;
      y1[c] = i10 * a + i11 * b;
      y2[c] = i20 * a + i21 * b + i22 * d;
    }
    for (int p = start[j] + 1; p < start[j + 1]; ++p) {
      const double* X = blocks + kBlock * p;
      double* __restrict t0 = Y + static_cast<long>(3 * rows[p]) * ld;
      double* __restrict t1 = t0 + ld;
      double* __restrict t2 = t1 + ld;
      const double x00 = X[0], x10 = X[1], x20 = X[2], x01 = X[4], x11 = X[5], x21 = X[6], x02 = X[8], x12 = X[9],
                   x22 = X[10];
#pragma omp simd
      for (int c = 0; c < m; ++c) {
        const double z0 = y0[c], z1 = y1[c], z2 = y2[c];
        t0[c] -= x00 * z0 + x01 * z1 + x02 * z2;
        t1[c] -= x10 * z0 + x11 * z1 + x12 * z2;
        t2[c] -= x20 * z0 + x21 * z1 + x22 * z2;
      }
    }
  }
}

void backward_many(int nv, const int* start, const int* rows, const double* blocks, const double* diagonal_inverse,
                   double* Y, int ld, int m) {
  for (int j = nv - 1; j >= 0; --j) {
    double* __restrict y0 = Y + static_cast<long>(3 * j) * ld;
    double* __restrict y1 = y0 + ld;
    double* __restrict y2 = y1 + ld;
    // s = y_j - sum_p L_p^T y_rows[p], in place, then y_j = L_jj^-T s.
    for (int p = start[j] + 1; p < start[j + 1]; ++p) {
      const double* X = blocks + kBlock * p;
      const double* __restrict t0 = Y + static_cast<long>(3 * rows[p]) * ld;
      const double* __restrict t1 = t0 + ld;
      const double* __restrict t2 = t1 + ld;
      const double x00 = X[0], x10 = X[1], x20 = X[2], x01 = X[4], x11 = X[5], x21 = X[6], x02 = X[8], x12 = X[9],
                   x22 = X[10];
#pragma omp simd
      for (int c = 0; c < m; ++c) {
        const double a = t0[c], b = t1[c], d = t2[c];
        y0[c] -= x00 * a + x10 * b + x20 * d;
        y1[c] -= x01 * a + x11 * b + x21 * d;
        y2[c] -= x02 * a + x12 * b + x22 * d;
      }
    }
    const double* I = diagonal_inverse + kBlock * j;
    const double i00 = I[0], i10 = I[1], i20 = I[2], i11 = I[5], i21 = I[6], i22 = I[10];
#pragma omp simd
    for (int c = 0; c < m; ++c) {
      const double s0 = y0[c], s1 = y1[c], s2 = y2[c];
      y0[c] = i00 * s0 + i10 * s1 + i20 * s2;
      y1[c] = i11 * s1 + i21 * s2;
      y2[c] = i22 * s2;
    }
  }
}

}  // namespace sinew::block_kernels
