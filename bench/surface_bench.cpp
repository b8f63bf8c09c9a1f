// Cost of the surface pipeline on the example blob (examples/meshes/blob.off, 642 vertices,
// 1280 faces): building the inside test, voxelising at 16/32/64 cells along the longest side
// (with and without the non-manifold option), embedding the surface in the lattice, and Gmsh
// tetrahedralisation at two max_edge values. Counters: elements (and vertices) produced.
#include <benchmark/benchmark.h>

#include "sinew/element/embedding.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/tetrahedralize_surface.hpp"
#include "sinew/mesh/voxelize.hpp"

namespace {

const sinew::TriangleSurface& blob() {
  static const sinew::TriangleSurface s = sinew::read_triangle_surface(SINEW_EXAMPLES "/meshes/blob.off");
  return s;
}

void BM_InsideTestBuild(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(sinew::InsideTest(blob()));
}
BENCHMARK(BM_InsideTestBuild)->Unit(benchmark::kMillisecond);

void BM_Voxelize(benchmark::State& state) {
  const sinew::InsideTest shape(blob());
  sinew::VoxelizeOptions o;
  o.resolution = static_cast<int>(state.range(0));
  o.non_manifold = state.range(1) != 0;
  sinew::VolumeMesh m;
  for (auto _ : state) m = sinew::voxelize_surface(shape, o);
  state.counters["hexes"] = static_cast<double>(m.num_elements());
  state.counters["vertices"] = static_cast<double>(m.num_vertices());
}
BENCHMARK(BM_Voxelize)->ArgsProduct({{16, 32, 64}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_EmbedSurface(benchmark::State& state) {
  sinew::VoxelizeOptions o;
  o.resolution = static_cast<int>(state.range(0));
  const sinew::VolumeMesh m = sinew::voxelize_surface(sinew::InsideTest(blob()), o);
  for (auto _ : state) benchmark::DoNotOptimize(sinew::embed_points(m, blob().vertices));
  state.counters["hexes"] = static_cast<double>(m.num_elements());
}
BENCHMARK(BM_EmbedSurface)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_Tetrahedralize(benchmark::State& state) {
  const double max_edge = static_cast<double>(state.range(0)) / 1000.0;
  sinew::VolumeMesh m;
  for (auto _ : state) m = sinew::tetrahedralize_surface(blob(), max_edge);
  state.counters["tets"] = static_cast<double>(m.num_elements());
}
BENCHMARK(BM_Tetrahedralize)->Arg(100)->Arg(30)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
