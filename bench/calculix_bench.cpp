// Peer benchmark: Sinew against CalculiX (Debian package calculix-ccx) on the same problem. An
// N x N x 2N block of hexahedra (edge 1/N, the block [0,1] x [0,1] x [0,2]) is stretched to
// `stretch` times its length in `increments` equal increments: the face z = 0 clamped, the face
// z = 2 moved along z with x and y held. Both codes use trilinear hexahedra with 2x2x2 Gauss
// points (CalculiX C3D8) and the decoupled Neo-Hookean energy
//   psi = C10 (I1bar - 3) + (J - 1)^2 / D1   (*HYPERELASTIC, NEO HOOKE; Sinew's
//   neo_hookean_decoupled), C10 = E / (4 (1 + nu)), D1 = 6 (1 - 2 nu) / E,
// so they solve the same discrete problem and their reaction forces on the moved face agree to
// the solvers' tolerances. Prints per size the wall times (medians of --repeats runs, the two
// codes alternating), Newton iterations per increment, the final reaction forces with their
// relative difference, and the time ratio.
//
//   calculix_bench [--sizes 8,16,24] [--repeats 3] [--E 1e5] [--nu 0.45] [--stretch 1.5]
//                  [--increments 5] [--threads 2] [--ccx ccx] [--linear cholmod|pcg]
//                  [--preconditioner multigrid] [--newton-tolerance 1e-3] [--keep DIR]
//
// CalculiX runs with its default convergence controls and --threads threads
// (OMP_NUM_THREADS, CCX_NPROC_STIFFNESS, CCX_NPROC_EQUATION_SOLVER); its wall time includes
// reading the input deck and writing its results, Sinew's includes building the model.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <numeric>
#include <regex>
#include <sstream>
#include <string>
#include <tbb/global_control.h>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/model/model.hpp"
#include "sinew/model/scene.hpp"

namespace {

using namespace sinew;
namespace fs = std::filesystem;

struct Settings {
  double E = 1e5, nu = 0.45, stretch = 1.5;
  int increments = 5, threads = 2, repeats = 3;
  std::string ccx = "ccx", linear = "cholmod", preconditioner = "multigrid";
  double newton_tolerance = 1e-3;
  std::string keep;
};

double C10(const Settings& s) { return s.E / (4.0 * (1.0 + s.nu)); }
double D1(const Settings& s) { return 6.0 * (1.0 - 2.0 * s.nu) / s.E; }

struct Run {
  double seconds = 0.0;
  std::vector<int> newton;  // per increment
  double reaction = 0.0;    // z force on the moved face at the end
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// ---- CalculiX ---------------------------------------------------------------------------

void write_deck(const fs::path& file, const VolumeMesh& mesh, int N, const Settings& s) {
  std::ofstream out(file);
  if (!out) throw Error("cannot write", file.string());
  out << "** " << N << " x " << N << " x " << 2 * N << " block, written by calculix_bench\n*NODE, NSET=NALL\n";
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    out << fmt::format("{}, {:.15g}, {:.15g}, {:.15g}\n", v + 1, mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
  // VTK_HEXAHEDRON and C3D8 number the nodes alike (bottom face, then top face).
  out << "*ELEMENT, TYPE=C3D8, ELSET=EALL\n";
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    out << e + 1;
    for (int a = 0; a < 8; ++a) out << ", " << mesh.elements(e, a) + 1;
    out << "\n";
  }
  const double top = mesh.vertices.col(2).maxCoeff();
  out << "*NSET, NSET=BOTTOM\n";
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.vertices(v, 2) == 0.0) out << v + 1 << "\n";
  out << "*NSET, NSET=TOP\n";
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    if (mesh.vertices(v, 2) == top) out << v + 1 << "\n";
  // Fields of at most 20 characters: CalculiX rejects longer ones.
  out << "*MATERIAL, NAME=NH\n*HYPERELASTIC, NEO HOOKE\n" << fmt::format("{:.12e}, {:.12e}\n", C10(s), D1(s));
  out << "*SOLID SECTION, ELSET=EALL, MATERIAL=NH\n";
  out << "*STEP, NLGEOM, INC=1000\n*STATIC, DIRECT\n" << fmt::format("{:.12g}, 1.0\n", 1.0 / s.increments);
  out << "*BOUNDARY\nBOTTOM, 1, 3\nTOP, 1, 2\n" << fmt::format("TOP, 3, 3, {:.15g}\n", (s.stretch - 1.0) * top);
  out << "*NODE PRINT, NSET=TOP, TOTALS=ONLY\nRF\n*END STEP\n";
}

Run run_calculix(const fs::path& dir, const Settings& s) {
  fs::remove(dir / "block.sta");
  fs::remove(dir / "block.dat");
  const std::string cmd = fmt::format(
      "cd '{}' && OMP_NUM_THREADS={} CCX_NPROC_STIFFNESS={} CCX_NPROC_EQUATION_SOLVER={} CCX_NPROC_RESULTS={} '{}' -i block "
      "> block.log 2>&1",
      dir.string(), s.threads, s.threads, s.threads, s.threads, s.ccx);
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  Run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0) throw Error(fmt::format("CalculiX failed (exit status {}); see {}", rc, (dir / "block.log").string()), s.ccx);
  // block.sta: STEP INC ATT ITRS ..., one line per attempt; iterations of every attempt count.
  std::ifstream sta(dir / "block.sta");
  std::map<int, int> per_increment;
  for (std::string line; std::getline(sta, line);) {
    std::istringstream ls(line);
    int step = 0, inc = 0, att = 0, itrs = 0;
    if (ls >> step >> inc >> att >> itrs) per_increment[inc] += itrs;
  }
  for (const auto& [inc, n] : per_increment) r.newton.push_back(n);
  // block.dat: "total force (fx,fy,fz) for set TOP and time ..." then the three totals.
  std::ifstream dat(dir / "block.dat");
  bool next = false;
  for (std::string line; std::getline(dat, line);) {
    if (line.find("total force") != std::string::npos) {
      next = true;
      continue;
    }
    std::istringstream ls(line);
    double fx = 0, fy = 0, fz = 0;
    if (next && (ls >> fx >> fy >> fz)) {
      r.reaction = fz;
      next = false;
    }
  }
  if (static_cast<int>(r.newton.size()) != s.increments || r.reaction == 0.0)
    throw Error(fmt::format("could not read {} increments and the reaction from block.sta/block.dat", s.increments),
                dir.string());
  return r;
}

// ---- Sinew --------------------------------------------------------------------------------

Scene block_scene(int N, const Settings& s) {
  Scene scene;
  scene.file = fmt::format("calculix_bench:N={}", N);
  scene.mesh.source = BoxShape{Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 1.0, 2.0)};
  scene.mesh.cells = Eigen::Vector3i(N, N, 2 * N);
  scene.material.family = "neo_hookean_decoupled";
  scene.material.parameters.values = {{"C10", C10(s)}, {"D1", D1(s)}};
  scene.boundary.push_back({"bottom", PlaneSelector{Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ()}, Pinned{}, {true, true, true}, {}});
  scene.boundary.push_back({"top", PlaneSelector{Eigen::Vector3d(0.0, 0.0, 2.0), Eigen::Vector3d::UnitZ()},
                            Translation{Eigen::Vector3d(0.0, 0.0, 2.0 * (s.stretch - 1.0) / s.increments)}, {true, true, true}, {}});
  scene.solver.newton.absolute_tolerance = s.newton_tolerance;
  scene.solver.newton.linear_tolerance = 1e-8;
  scene.solver.linear.kind = s.linear;
  scene.solver.linear.preconditioner = s.preconditioner;
  scene.solver.linear.max_iterations = 10000;
  scene.frames = s.increments;
  scene.output.vtu = false;
  scene.output.obj = false;
  return scene;
}

Run run_sinew(int N, const Settings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  Model m = build_model(block_scene(N, s));
  State state = m.initial;
  Run r;
  for (int frame = 1; frame <= s.increments; ++frame) {
    const StepStats stats = m.integrator->advance_frame(state, frame, {});
    if (!stats.converged) throw Error(fmt::format("increment {} did not converge: {}", frame, stats.failure), "Sinew");
    r.newton.push_back(stats.newton_iterations);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // The reaction on the moved face: the elastic force its prescribed vertices feel.
  Eigen::VectorXd g = Eigen::VectorXd::Zero(state.x.size());
  m.hyperelastic->add_gradient(state.x, g);
  for (int v : m.kinematics->at(1).vertices) r.reaction += g(3 * v + 2);
  return r;
}

std::string list(const std::vector<int>& v) {
  std::string out;
  for (int n : v) out += (out.empty() ? "" : "+") + std::to_string(n);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Sinew against CalculiX on a stretched block (same mesh, element and energy)");
  std::string sizes = "8,16,24";
  Settings s;
  app.add_option("--sizes", sizes, "block sizes N (N x N x 2N hexahedra), comma-separated");
  app.add_option("--repeats", s.repeats, "runs of each code per size (medians reported)")->check(CLI::PositiveNumber);
  app.add_option("--E", s.E, "Young's modulus")->check(CLI::PositiveNumber);
  app.add_option("--nu", s.nu, "Poisson ratio")->check(CLI::Range(0.0, 0.4999));
  app.add_option("--stretch", s.stretch, "final length / rest length")->check(CLI::Range(1.0, 4.0));
  app.add_option("--increments", s.increments, "equal load increments")->check(CLI::PositiveNumber);
  app.add_option("--threads", s.threads, "threads for both codes")->check(CLI::PositiveNumber);
  app.add_option("--ccx", s.ccx, "the CalculiX executable");
  app.add_option("--linear", s.linear, "Sinew's linear solver")->check(CLI::IsMember({"cholmod", "pcg"}));
  app.add_option("--preconditioner", s.preconditioner, "with --linear pcg");
  app.add_option("--newton-tolerance", s.newton_tolerance, "Sinew's absolute Newton tolerance (force norm)");
  app.add_option("--keep", s.keep, "directory for the CalculiX decks and results (default: a removed temporary one)");
  CLI11_PARSE(app, argc, argv);

  try {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(s.threads));
    fs::path dir;
    if (s.keep.empty()) {
      std::string pattern = (fs::temp_directory_path() / "sinew_calculix_XXXXXX").string();
      if (!mkdtemp(pattern.data())) throw Error("cannot make a temporary directory", pattern);
      dir = pattern;
    } else {
      dir = s.keep;
      fs::create_directories(dir);
    }
    struct Row {
      int N = 0;
      long hexes = 0, dofs = 0;
      Run ccx, sinew;
      double ccx_seconds = 0, sinew_seconds = 0;
    };
    std::vector<Row> rows;
    std::stringstream ss(sizes);
    for (std::string item; std::getline(ss, item, ',');) {
      const int N = std::stoi(item);
      if (N < 1) throw Error("sizes must be positive", "--sizes");
      const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 1.0, 2.0), Eigen::Vector3i(N, N, 2 * N));
      const fs::path deck_dir = dir / fmt::format("N{}", N);
      fs::create_directories(deck_dir);
      write_deck(deck_dir / "block.inp", mesh, N, s);
      Row row;
      row.N = N;
      row.hexes = mesh.num_elements();
      row.dofs = 3 * mesh.num_vertices();
      std::vector<double> tc, ts;
      for (int k = 0; k < s.repeats; ++k) {
        std::fprintf(stderr, "N = %d, run %d/%d: CalculiX ...", N, k + 1, s.repeats);
        row.ccx = run_calculix(deck_dir, s);
        tc.push_back(row.ccx.seconds);
        std::fprintf(stderr, " %.2f s (%s Newton); Sinew ...", row.ccx.seconds, list(row.ccx.newton).c_str());
        row.sinew = run_sinew(N, s);
        ts.push_back(row.sinew.seconds);
        std::fprintf(stderr, " %.2f s (%s Newton)\n", row.sinew.seconds, list(row.sinew.newton).c_str());
      }
      row.ccx_seconds = median(tc);
      row.sinew_seconds = median(ts);
      rows.push_back(row);
    }
    if (s.keep.empty()) fs::remove_all(dir);

    std::printf("\nBlock N x N x 2N stretched to %.3g in %d increments; decoupled Neo-Hookean C10 = %.6g, D1 = %.6g "
                "(E = %g, nu = %g); C3D8 / Hex8 2x2x2 Gauss; %d threads each; medians of %d runs.\n"
                "Sinew: %s%s, Newton |residual| < %g; CalculiX: default controls.\n\n",
                s.stretch, s.increments, C10(s), D1(s), s.E, s.nu, s.threads, s.repeats, s.linear.c_str(),
                s.linear == "pcg" ? (" (" + s.preconditioner + ")").c_str() : "", s.newton_tolerance);
    std::printf("| N | hexahedra | DOFs | CalculiX s | CalculiX Newton | Sinew s | Sinew Newton | CalculiX / Sinew time | "
                "reaction CalculiX | reaction Sinew | rel. difference |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Row& r : rows) {
      const int nc = std::accumulate(r.ccx.newton.begin(), r.ccx.newton.end(), 0);
      const int ns = std::accumulate(r.sinew.newton.begin(), r.sinew.newton.end(), 0);
      std::printf("| %d | %ld | %ld | %.2f | %d (%s) | %.2f | %d (%s) | %.2f | %.6e | %.6e | %.1e |\n", r.N, r.hexes, r.dofs,
                  r.ccx_seconds, nc, list(r.ccx.newton).c_str(), r.sinew_seconds, ns, list(r.sinew.newton).c_str(),
                  r.ccx_seconds / r.sinew_seconds, r.ccx.reaction, r.sinew.reaction,
                  std::abs(r.sinew.reaction - r.ccx.reaction) / std::abs(r.ccx.reaction));
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "calculix_bench: error: %s\n", e.what());
    return 2;
  }
}
