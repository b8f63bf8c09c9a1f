#pragma once
// Preconditioners for the iterative linear solvers, chosen by name from a registry. A new one
// (multigrid, AMG, a GPU backend's) implements Preconditioner and is registered under a name;
// PCG and the scene reader then accept it without changes (docs/solvers.md).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sinew/linalg/linear_operator.hpp"
#include "sinew/solver/solver_context.hpp"

namespace sinew {

class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  // The name it is registered under.
  virtual std::string name() const = 0;
  // Prepares for solves with A, once per linear solve (each Newton iteration brings a new A).
  // It may keep what it built for earlier matrices (a lagged factorisation). A and the context
  // are valid until the next setup.
  virtual void setup(const LinearOperator& A, const SolverContext& context) = 0;
  // z = M^-1 r for a symmetric positive definite M approximating A.
  virtual void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) = 0;
};

using PreconditionerFactory = std::function<std::unique_ptr<Preconditioner>()>;

// Adds `name` to the registry (thread-safe); a sinew::Error if the name is taken or empty.
// The built-in ones (jacobi, block_jacobi, lagged_cholesky, multigrid, amg) are always registered.
void register_preconditioner(const std::string& name, const std::string& description, PreconditionerFactory factory);
// A new preconditioner of kind `name`; a sinew::Error listing the registered names if unknown.
std::unique_ptr<Preconditioner> make_preconditioner(const std::string& name);
// The registered names, in registration order (built-in ones first).
std::vector<std::string> registered_preconditioners();
// A one-line description of a registered preconditioner ("" if unknown).
std::string preconditioner_description(const std::string& name);

}  // namespace sinew
