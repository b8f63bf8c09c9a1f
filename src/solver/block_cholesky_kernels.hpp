#pragma once
// The numeric kernels of BlockCholesky on plain arrays, in a file of their own so that it can be
// compiled for the build machine's vector width (CMake option SINEW_NATIVE_KERNELS) without
// Eigen's or the standard library's inline templates in it (they would be compiled twice, for two
// instruction sets, and the linker keeps either).
//
// A 3x3 block is stored padded to 4 rows, column-major: entry (r, c) at 4 c + r, r = 3 always 0,
// so each of its columns is one 4-wide vector (AVX) or two 2-wide ones (SSE2). Vectors are
// padded likewise: vertex v's three entries at 4 v, 4 v + 1, 4 v + 2, and 4 v + 3 is 0.
namespace sinew::block_kernels {

constexpr int kBlock = 12;  // doubles per padded block

// L by block columns (the elimination order): column j's blocks are [start[j], start[j + 1]),
// the first its diagonal block, rows[] their block rows, ascending. On entry `blocks` holds the
// lower triangle of the matrix at L's pattern (fill zero), on exit L with the diagonal blocks'
// Cholesky factors and `diagonal_inverse` their inverses. `work` holds 4 nv ints. False if the
// matrix is not positive definite.
bool factorize(int nv, const int* start, const int* rows, double* blocks, double* diagonal_inverse, int* work);

// y = L^-1 y from block column `first` on (the blocks before it are zero), in place.
void forward(int nv, const int* start, const int* rows, const double* blocks, const double* diagonal_inverse, double* y,
             int first);
// y = L^-T y, in place.
void backward(int nv, const int* start, const int* rows, const double* blocks, const double* diagonal_inverse, double* y);

// The same for m right-hand sides at once, Y row-major: vertex v's three rows start at
// Y + 3 v ld, each with the m columns side by side, so that a block of L is read once for all
// of them and each update is a vector operation over the columns. forward_many skips the
// vertices whose rows are zero in every column (sparse right-hand sides).
void forward_many(int nv, const int* start, const int* rows, const double* blocks, const double* diagonal_inverse,
                  double* Y, int ld, int m);
void backward_many(int nv, const int* start, const int* rows, const double* blocks, const double* diagonal_inverse,
                   double* Y, int ld, int m);

}  // namespace sinew::block_kernels
