// Assembly and operator throughput on a hexahedral lattice (issue 12's "hexahedra per second"):
// the projected Hessian (Stable Neo-Hookean, nu = 0.49, per-quadrature-point eigen-clamp), the
// gradient, the energy, one product with the assembled matrix, and the matrix's bytes per
// hexahedron, at a stretched and randomly perturbed state where about half the quadrature
// points are indefinite (as in the stretch test). Medians of --repeats runs. With
// --matrix-free also the matrix-free Hessian (element matrices kept in single precision):
// its set-up time, one product and its bytes per hexahedron. Also the multigrid's first Galerkin
// product P^T A P (the lattice coarsened once, the z = 0 face's DOFs fixed), which each Newton
// iteration's preconditioner setup pays. The digests (FNV-1a of the values'
// bits) tell whether two builds assemble bitwise the same Hessian and gradient.
//
//   assembly_bench [--sizes 16,33] [--repeats 5] [--threads N] [--matrix-free] [--cpu-time]
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <random>

#include "sinew/assembly/problem.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/linalg/galerkin_product.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/solver/lattice_hierarchy.hpp"

namespace {

using namespace sinew;
using Clock = std::chrono::steady_clock;

bool cpu_clock = false;  // --cpu-time

// Wall seconds, or with --cpu-time the process's CPU seconds (all threads together).
double seconds_now() {
  if (cpu_clock) return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

template <class F>
double median_seconds(int repeats, const F& f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const double start = seconds_now();
    f();
    t.push_back(seconds_now() - start);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// FNV-1a over the bits of n doubles.
std::uint64_t digest(const double* values, Eigen::Index n) {
  std::uint64_t h = 14695981039346656037ull;
  for (Eigen::Index i = 0; i < n; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, values + i, sizeof bits);
    for (int byte = 0; byte < 8; ++byte) h = (h ^ ((bits >> (8 * byte)) & 0xffu)) * 1099511628211ull;
  }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Assembly and operator throughput on an N x N x N hexahedral lattice");
  std::vector<int> sizes = {16, 33};
  int repeats = 5, threads = 0;
  bool matrix_free = false;
  app.add_option("--sizes", sizes, "lattice cells per side")->delimiter(',');
  app.add_option("--repeats", repeats, "runs per measurement (median reported)");
  app.add_option("--threads", threads, "worker threads (default: all cores)");
  app.add_flag("--matrix-free", matrix_free, "also measure the matrix-free Hessian");
  app.add_flag("--cpu-time", cpu_clock,
               "report process CPU time instead of wall time: steadier on a shared machine, and with "
               "--threads 1 the work of one thread");
  CLI11_PARSE(app, argc, argv);
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

  MaterialSpec spec;
  spec.family = "stable_neo_hookean";
  spec.target = YoungPoisson{1e5, 0.49};
  const auto material = build_material(spec);
  fmt::print("{:>4} {:>9} {:>10} {:>12} {:>12} {:>12} {:>12} {:>12} {:>10}\n", "N", "hexes", "DOFs", "hessian ms",
             "M hex/s", "gradient ms", "energy ms", "product ms", "B/hex");
  for (int n : sizes) {
    const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(1.0), Eigen::Vector3i::Constant(n));
    auto disc = std::make_shared<Discretization>(mesh);
    Problem problem(mesh.num_vertices());
    problem.add_form(std::make_shared<ElasticForm>(disc, material, Projection::Clamp));
    Eigen::VectorXd x = mesh.rest_positions();
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-0.15, 0.15);
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
      x(3 * v) *= 1.8;  // stretched along x, thinning across
      x(3 * v + 1) *= 0.75;
      x(3 * v + 2) *= 0.75;
      for (int i = 0; i < 3; ++i) x(3 * v + i) += u(rng) / n;
    }
    const LinearOperator* op = &problem.hessian(x);  // pattern and scatter maps, outside the timing
    const double hessian = median_seconds(repeats, [&] { op = &problem.hessian(x); });
    const double gradient = median_seconds(repeats, [&] { (void)problem.gradient(x); });
    const double energy = median_seconds(repeats, [&] { (void)problem.value(x); });
    Eigen::VectorXd p = Eigen::VectorXd::Random(x.size()), y(x.size());
    const double product = median_seconds(std::max(repeats, 10), [&] { op->apply(p, y); });
    const Eigen::SparseMatrix<double>& A = *op->matrix();
    const double bytes = static_cast<double>(A.nonZeros()) * (sizeof(double) + sizeof(int)) +
                         static_cast<double>(A.outerSize() + 1) * sizeof(int);
    const double hexes = static_cast<double>(disc->num_elements());
    fmt::print("{:>4} {:>9} {:>10} {:>12.1f} {:>12.3f} {:>12.1f} {:>12.1f} {:>12.2f} {:>10.0f}\n", n,
               disc->num_elements(), x.size(), 1e3 * hessian, hexes / hessian * 1e-6, 1e3 * gradient, 1e3 * energy,
               1e3 * product, bytes / hexes);
    fmt::print("     product: {:.2f} M hex/s; gradient {:.3f} M hex/s; energy {:.3f} M hex/s\n", hexes / product * 1e-6,
               hexes / gradient * 1e-6, hexes / energy * 1e-6);
    const Eigen::VectorXd g = problem.gradient(x);
    // The first Galerkin product, outside the timing: its symbolic part (pattern, orders).
    const LatticeHierarchy hierarchy = lattice_hierarchy(mesh, 1, 2);
    const VertexInterpolation& P = hierarchy.interpolations.at(0);
    std::vector<char> fine_free(static_cast<size_t>(x.size()), 1);
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
      if (mesh.vertices(v, 2) == 0.0)
        for (int i = 0; i < 3; ++i) fine_free[static_cast<size_t>(3 * v + i)] = 0;
    const std::vector<char> coarse_free = P.coarse_free(fine_free);
    const GalerkinProduct galerkin(block_pattern(A), P);
    BlockSparseMatrix C = galerkin.make_coarse();
    const double coarse = median_seconds(repeats, [&] { galerkin.compute(A, fine_free, coarse_free, C); });
    fmt::print("     Galerkin P^T A P: {:.1f} ms ({:.3f} M hex/s)\n", 1e3 * coarse, hexes / coarse * 1e-6);
    fmt::print("     digests: hessian {:016x}, gradient {:016x}, Galerkin {:016x}\n", digest(A.valuePtr(), A.nonZeros()),
               digest(g.data(), g.size()), digest(C.block(0).data(), 9 * C.num_blocks()));
    if (!matrix_free) continue;
    const Eigen::VectorXd assembled_y = y;
    problem.set_matrix_free(true);
    const LinearOperator* free_op = &problem.hessian(x);
    const double setup = median_seconds(repeats, [&] { free_op = &problem.hessian(x); });
    const double free_product = median_seconds(std::max(repeats, 10), [&] { free_op->apply(p, y); });
    fmt::print("     matrix-free: set-up {:.1f} ms ({:.3f} M hex/s), product {:.2f} ms ({:.2f} M hex/s), {:.0f} B/hex, "
               "product differs from the assembled one by {:.1e} (relative)\n",
               1e3 * setup, hexes / setup * 1e-6, 1e3 * free_product, hexes / free_product * 1e-6,
               static_cast<double>(problem.hessian_bytes()) / hexes, (y - assembled_y).norm() / assembled_y.norm());
  }
  return 0;
}
