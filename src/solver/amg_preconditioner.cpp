#include "sinew/solver/amg_preconditioner.hpp"

#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_parcsr_ls.h>
#include <_hypre_parcsr_ls.h>  // hypre_ParAMGData: levels and operator complexity after setup

#include <fmt/format.h>

#include <numeric>
#include <type_traits>

#include "sinew/core/error.hpp"
#include "sinew/solver/hypre_runtime.hpp"

namespace sinew {

// Eigen's indices go to hypre as they are (Debian's hypre: 32-bit indices, double values).
static_assert(std::is_same_v<HYPRE_BigInt, int> && std::is_same_v<HYPRE_Int, int> &&
                  std::is_same_v<HYPRE_Complex, double>,
              "hypre built with other index or value types");

namespace {

HYPRE_IJVector make_vector(HYPRE_Int n) {
  HYPRE_IJVector v = nullptr;
  HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, n - 1, &v);
  HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR);
  HYPRE_IJVectorInitialize(v);
  HYPRE_IJVectorAssemble(v);
  return v;
}

HYPRE_ParVector par_vector(HYPRE_IJVector v) {
  void* object = nullptr;
  HYPRE_IJVectorGetObject(v, &object);
  return static_cast<HYPRE_ParVector>(object);
}

}  // namespace

struct AmgPreconditioner::Hypre {
  HYPRE_Int n = 0;
  std::vector<HYPRE_BigInt> index;  // 0 .. n - 1, the rows and vector entries set at once
  HYPRE_IJMatrix A = nullptr;
  HYPRE_IJVector b = nullptr, x = nullptr;
  std::vector<HYPRE_IJVector> modes;  // rigid-body rotations (alive as long as the solver)
  std::vector<HYPRE_ParVector> mode_objects;  // their ParVectors, the array hypre is given
  HYPRE_Solver amg = nullptr;

  ~Hypre() {
    if (hypre_finalized()) return;  // at exit, after MPI_Finalize: leave the memory to the OS
    const auto lock = hypre_lock();
    release();
  }
  // The hierarchy and the matrix (vectors stay while the size does).
  void release_solver() {
    if (amg) HYPRE_BoomerAMGDestroy(amg);
    amg = nullptr;
    for (HYPRE_IJVector v : modes) HYPRE_IJVectorDestroy(v);
    modes.clear();
    mode_objects.clear();
    if (A) HYPRE_IJMatrixDestroy(A);
    A = nullptr;
  }
  void release() {
    release_solver();
    if (b) HYPRE_IJVectorDestroy(b);
    if (x) HYPRE_IJVectorDestroy(x);
    b = x = nullptr;
    n = 0;
  }
};

AmgPreconditioner::AmgPreconditioner(AmgSettings settings) : settings_(settings) {}
AmgPreconditioner::~AmgPreconditioner() = default;

void AmgPreconditioner::setup(const LinearOperator& op, const SolverContext& context) {
  const Eigen::SparseMatrix<double>* matrix = op.matrix();
  if (!matrix) throw Error("needs the assembled matrix (use block_jacobi with a matrix-free operator)", "preconditioner amg");
  if (op.rows() % 3 != 0) throw Error("expects 3 DOFs per vertex", "preconditioner amg");
  if (op.rows() == 0) throw Error("the system is empty", "preconditioner amg");
  ensure_hypre_initialized();
  const auto lock = hypre_lock();
  if (!hypre_) hypre_ = std::make_unique<Hypre>();
  Hypre& h = *hypre_;
  h.release_solver();
  const HYPRE_Int n = static_cast<HYPRE_Int>(op.rows());
  if (h.n != n) {
    h.release();
    h.n = n;
    h.index.resize(static_cast<size_t>(n));
    std::iota(h.index.begin(), h.index.end(), 0);
    h.b = make_vector(n);
    h.x = make_vector(n);
  }

  // The matrix, row by row: the matrix is symmetric, so column c of Eigen's column-major
  // storage is row c. One process owns all rows, so every entry is in hypre's diagonal part.
  Eigen::SparseMatrix<double> compressed;
  const Eigen::SparseMatrix<double>* M = matrix;
  if (!matrix->isCompressed()) {
    compressed = *matrix;
    compressed.makeCompressed();
    M = &compressed;
  }
  std::vector<HYPRE_Int> row_sizes(static_cast<size_t>(n)), no_offdiag(static_cast<size_t>(n), 0);
  for (HYPRE_Int c = 0; c < n; ++c) row_sizes[static_cast<size_t>(c)] = M->outerIndexPtr()[c + 1] - M->outerIndexPtr()[c];
  HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, n - 1, 0, n - 1, &h.A);
  HYPRE_IJMatrixSetObjectType(h.A, HYPRE_PARCSR);
  HYPRE_IJMatrixSetDiagOffdSizes(h.A, row_sizes.data(), no_offdiag.data());
  HYPRE_IJMatrixInitialize(h.A);
  HYPRE_IJMatrixSetValues(h.A, n, row_sizes.data(), h.index.data(), M->innerIndexPtr(), M->valuePtr());
  if (HYPRE_IJMatrixAssemble(h.A) != 0) {
    HYPRE_ClearAllErrors();
    throw Error("hypre could not assemble the matrix", "preconditioner amg");
  }
  void* object = nullptr;
  HYPRE_IJMatrixGetObject(h.A, &object);
  const auto A = static_cast<HYPRE_ParCSRMatrix>(object);

  HYPRE_BoomerAMGCreate(&h.amg);
  HYPRE_Solver amg = h.amg;
  HYPRE_BoomerAMGSetPrintLevel(amg, 0);
  HYPRE_BoomerAMGSetMaxIter(amg, 1);  // one V-cycle per application, from a zero guess
  HYPRE_BoomerAMGSetTol(amg, 0.0);
  HYPRE_BoomerAMGSetMaxLevels(amg, settings_.max_levels);
  HYPRE_BoomerAMGSetCoarsenType(amg, settings_.coarsen_type);
  HYPRE_BoomerAMGSetAggNumLevels(amg, settings_.aggressive_levels);
  HYPRE_BoomerAMGSetStrongThreshold(amg, settings_.strong_threshold);
  HYPRE_BoomerAMGSetInterpType(amg, settings_.interp_type);
  HYPRE_BoomerAMGSetPMaxElmts(amg, settings_.max_interp_elements);
  HYPRE_BoomerAMGSetRelaxType(amg, settings_.relax_type);
  HYPRE_BoomerAMGSetNumSweeps(amg, settings_.sweeps);
  HYPRE_BoomerAMGSetCycleRelaxType(amg, 9, 3);  // the coarsest level: Gaussian elimination
  // Systems AMG: unknowns interleaved x, y, z per vertex, which is hypre's default order.
  // Nodal coarsening (optional): a vertex is coarse or fine as a whole.
  HYPRE_BoomerAMGSetNumFunctions(amg, 3);
  if (settings_.nodal > 0) {
    HYPRE_BoomerAMGSetNodal(amg, settings_.nodal);
    HYPRE_BoomerAMGSetNodalDiag(amg, 1);
  }

  // Rotations about the rest shape's centroid (translations are the unknown-based
  // interpolation's constants already), zero on fixed DOFs, as the constrained operator's
  // near-null space.
  used_rbm_ = false;
  const bool mesh_known = context.discretization && 3 * context.discretization->mesh().num_vertices() == op.rows();
  if (settings_.rigid_body_modes && settings_.nodal > 0 && mesh_known) {
    const Eigen::MatrixX3d& p = context.discretization->mesh().vertices;
    const Eigen::RowVector3d centre = p.colwise().mean();
    const double scale = std::max((p.rowwise() - centre).cwiseAbs().maxCoeff(), 1e-300);
    std::vector<double> mode(static_cast<size_t>(n));
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d w = Eigen::Vector3d::Unit(axis);
      for (Eigen::Index v = 0; v < p.rows(); ++v) {
        const Eigen::Vector3d u = w.cross(((p.row(v) - centre) / scale).transpose());
        for (int i = 0; i < 3; ++i) mode[static_cast<size_t>(3 * v + i)] = context.is_fixed(3 * v + i) ? 0.0 : u(i);
      }
      HYPRE_IJVector vec = make_vector(n);
      HYPRE_IJVectorSetValues(vec, n, h.index.data(), mode.data());
      HYPRE_IJVectorAssemble(vec);
      h.modes.push_back(vec);
    }
    h.mode_objects.clear();
    for (HYPRE_IJVector v : h.modes) h.mode_objects.push_back(par_vector(v));
    HYPRE_BoomerAMGSetInterpVecVariant(amg, 2);  // GM-2
    HYPRE_BoomerAMGSetInterpVecQMax(amg, 4);
    HYPRE_BoomerAMGSetSmoothInterpVectors(amg, 1);
    HYPRE_BoomerAMGSetInterpRefine(amg, 1);
    // hypre keeps the array (the finest level's vectors stay the caller's): it lives in Hypre.
    HYPRE_BoomerAMGSetInterpVectors(amg, static_cast<HYPRE_Int>(h.mode_objects.size()), h.mode_objects.data());
    used_rbm_ = true;
  }

  // Coarse levels may be singular (a floating piece, round-off); hypre reports that as an error
  // in setup yet handles it in the cycle, as MFEM notes, so setup errors are not fatal.
  HYPRE_BoomerAMGSetup(amg, A, par_vector(h.b), par_vector(h.x));
  HYPRE_ClearAllErrors();

  const auto* data = reinterpret_cast<hypre_ParAMGData*>(amg);
  levels_ = hypre_ParAMGDataNumLevels(data);
  double nnz = 0.0, fine = 0.0;
  for (int l = 0; l < levels_; ++l) {
    hypre_ParCSRMatrix* Al = hypre_ParAMGDataAArray(data)[l];
    const double level_nnz = static_cast<double>(hypre_CSRMatrixNumNonzeros(hypre_ParCSRMatrixDiag(Al)) +
                                                 hypre_CSRMatrixNumNonzeros(hypre_ParCSRMatrixOffd(Al)));
    nnz += level_nnz;
    if (l == 0) fine = level_nnz;
  }
  complexity_ = fine > 0.0 ? nnz / fine : 0.0;
}

void AmgPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  if (!hypre_ || !hypre_->amg) throw Error("apply before setup", "preconditioner amg");
  Hypre& h = *hypre_;
  if (r.size() != h.n) throw Error(fmt::format("a vector of {} entries for a system of {}", r.size(), h.n), "preconditioner amg");
  const auto lock = hypre_lock();
  HYPRE_IJVectorSetValues(h.b, h.n, h.index.data(), r.data());
  HYPRE_ParVectorSetConstantValues(par_vector(h.x), 0.0);
  void* object = nullptr;
  HYPRE_IJMatrixGetObject(h.A, &object);
  HYPRE_BoomerAMGSolve(h.amg, static_cast<HYPRE_ParCSRMatrix>(object), par_vector(h.b), par_vector(h.x));
  HYPRE_ClearAllErrors();  // "not converged" after its one cycle is the intent, not an error
  z.resize(r.size());
  HYPRE_IJVectorGetValues(h.x, h.n, h.index.data(), z.data());
}

}  // namespace sinew
