// Cost of one material evaluation, per catalog family (registered at runtime, so every family
// added to the catalog is measured): psi only, psi + P, and evaluate(F, Clamp) (psi + P +
// clamped Hessian, what a projected-Newton solver asks for). Also the nonlinearity-exponent
// wrapper (paper 002 Eq. 16-18) and a mix (Eq. 20) on linear corotational, to show their
// overhead. Each iteration takes the next F of a precomputed pool of random F with J > 0.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "sinew/material/catalog.hpp"
#include "sinew/material/mixing.hpp"
#include "sinew/material/nonlinearity.hpp"

namespace {

using sinew::Mat3;
using sinew::Material;
using sinew::Vec3;

// Random rotations times stretches in [0.6, 1.6]: every family's domain, moderate strain.
const std::vector<Mat3>& pool() {
  static const std::vector<Mat3> Fs = [] {
    std::mt19937 rng(2024);
    std::normal_distribution<double> n(0.0, 1.0);
    std::uniform_real_distribution<double> u(0.6, 1.6);
    auto rotation = [&] {
      Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
      q.normalize();
      return Mat3(q.toRotationMatrix());
    };
    std::vector<Mat3> out;
    for (int k = 0; k < 1024; ++k) {
      out.push_back(rotation() * Vec3(u(rng), u(rng), u(rng)).asDiagonal() *
                    rotation().transpose());
    }
    return out;
  }();
  return Fs;
}

enum class Work { Psi, PsiP, Evaluate };

void run(benchmark::State& state, const std::shared_ptr<const Material>& m, Work work) {
  const auto& Fs = pool();
  std::size_t k = 0;
  for (auto _ : state) {
    const Mat3& F = Fs[k++ & (Fs.size() - 1)];
    switch (work) {
      case Work::Psi: benchmark::DoNotOptimize(m->psi(F)); break;
      case Work::PsiP: {
        const double psi = m->psi(F);
        const Mat3 P = m->pk1(F);
        benchmark::DoNotOptimize(psi);
        benchmark::DoNotOptimize(P.data());
        break;
      }
      case Work::Evaluate: {
        const sinew::Evaluation e = m->evaluate(F, sinew::Projection::Clamp);
        benchmark::DoNotOptimize(e.hessian.data());
        break;
      }
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

void register_material(const std::string& name, std::shared_ptr<const Material> m) {
  for (const auto& [label, work] : {std::pair{"psi", Work::Psi}, std::pair{"psi+P", Work::PsiP},
                                    std::pair{"evaluate_clamp", Work::Evaluate}}) {
    benchmark::RegisterBenchmark((name + "/" + label).c_str(),
                                 [m, w = work](benchmark::State& s) { run(s, m, w); });
  }
}

}  // namespace

int main(int argc, char** argv) {
  const auto& catalog = sinew::MaterialCatalog::instance();
  for (const auto& info : catalog.all()) {
    register_material(info.name, std::shared_ptr<const Material>(catalog.make(info.name)));
  }
  const auto lc = std::shared_ptr<const Material>(catalog.make("linear_corotational"));
  register_material("linear_corotational[alpha=2]",
                    std::make_shared<sinew::NonlinearMaterial>(lc, 2.0));
  const auto& lc_info = catalog.find("linear_corotational");
  register_material("mix[linear_corotational x2, alpha 2/0.5]",
                    sinew::make_mixed_material(lc_info, {}, lc_info, {}, {10.0, 1.0}, 2.0, 0.5));

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
