// make_linear_solver: the direct solver or PCG with a preconditioner from the registry.
#include "sinew/solver/linear_solver.hpp"

#include "sinew/core/error.hpp"
#include "sinew/solver/pcg_solver.hpp"

namespace sinew {

std::unique_ptr<LinearSolver> make_cholmod_solver();

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverSettings& s) {
  if (s.kind == "cholmod") return make_cholmod_solver();
  if (s.kind == "pcg") return std::make_unique<PcgSolver>(make_preconditioner(s.preconditioner), s.max_iterations);
  throw Error("unknown linear solver '" + s.kind + "' (expected cholmod or pcg)", "solver.linear");
}

}  // namespace sinew
