// The batched hexahedron stiffness kernel alone (forms/hex_invariant_stiffness), without the
// matrix: microseconds per element in one thread with its inputs hot in cache, for each
// projection and for the single and the paired call. Set beside assembly_bench's Hessian time
// per hexahedron, it splits the assembly into the kernel and the rest (gathering, the scatter into
// the matrix, cache misses); set against Projection::None it prices the projection (SVD, mode
// shifts). Stable Neo-Hookean, nu = 0.49, at assembly_bench's stretched and perturbed state.
//
//   element_kernel_bench [--repeats 7] [--calls 20000]
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <random>
#include <vector>

#include "forms/hex_invariant_stiffness.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"

using namespace sinew;

int main(int argc, char** argv) {
  CLI::App app("The batched hexahedron stiffness kernel alone: microseconds per element, one thread, hot cache");
  int repeats = 7, calls = 20000;
  app.add_option("--repeats", repeats, "timed runs per case (the fastest is reported)")->check(CLI::PositiveNumber);
  app.add_option("--calls", calls, "kernel calls per timed run")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  MaterialSpec spec;
  spec.family = "stable_neo_hookean";
  spec.target = YoungPoisson{1e5, 0.49};
  const auto material = build_material(spec);
  const auto* invariant = dynamic_cast<const InvariantMaterial*>(material.get());
  if (!invariant) return 1;

  // 64 elements of an 8^3 lattice, cycled through: their inputs and outputs stay in L1/L2.
  const int n = 8, cycled = 64;
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(1.0), Eigen::Vector3i::Constant(n));
  const Discretization d(mesh);
  Eigen::VectorXd x = mesh.rest_positions();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    x(3 * v) *= 1.8;
    x(3 * v + 1) *= 0.75;
    x(3 * v + 2) *= 0.75;
    for (int i = 0; i < 3; ++i) x(3 * v + i) += u(rng) / n;
  }
  std::vector<HexGradientLanes> lanes(cycled);
  std::vector<fixed_element::Positions<8>> xe(cycled);
  for (int e = 0; e < cycled; ++e) {
    lanes[e] = hex_gradient_lanes(d, e);
    for (int a = 0; a < 8; ++a) xe[e].col(a) = x.segment<3>(3 * mesh.elements(e, a));
  }

  fmt::print("{:>8} {:>8} {:>14}\n", "projection", "call", "us/element");
  const std::pair<Projection, const char*> modes[] = {
      {Projection::None, "none"}, {Projection::Clamp, "clamp"}, {Projection::Abs, "abs"}};
  for (const auto& [mode, name] : modes) {
    for (const bool pair : {false, true}) {
      double best = 1e300;
      fixed_element::SymmetricBlocks<8> K0, K1;
      for (int r = 0; r < repeats; ++r) {
        const auto start = std::chrono::steady_clock::now();
        bool ok = true;
        for (int c = 0; c < calls; ++c) {
          const int e = (2 * c) % cycled;
          K0.set_zero();
          if (pair) {
            K1.set_zero();
            ok &= add_hex_invariant_stiffness_pair(*invariant, mode, lanes[e], xe[e], K0, lanes[e + 1], xe[e + 1], K1);
          } else {
            ok &= add_hex_invariant_stiffness(*invariant, mode, lanes[e], xe[e], K0);
          }
          asm volatile("" : : "r"(&K0), "r"(&K1) : "memory");  // the results count
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!ok) {
          fmt::print(stderr, "the kernel refused an element\n");
          return 1;
        }
        best = std::min(best, seconds / (static_cast<double>(calls) * (pair ? 2 : 1)));
      }
      fmt::print("{:>8} {:>8} {:>14.3f}\n", name, pair ? "pair" : "single", 1e6 * best);
    }
  }
  return 0;
}
