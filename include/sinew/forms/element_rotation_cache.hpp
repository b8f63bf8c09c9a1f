#pragma once
// Per-element polar decompositions (the corotational rotation R and its signed SVD) kept for the
// positions they were last computed at. One time step of paper 001's stepper asks for the same
// rotations many times: K and f at x0, then per SQP iterate every element energy, the constraint
// Jacobians and the Lagrangian Hessian's element blocks at x_k, and the step's last iterate is the
// next step's x0. On its small scenes the 3x3 SVDs were ~10 % of the process.
//
// An entry is keyed by the 12 coordinates it was computed from (the innermost tetrahedron's four
// corners), compared exactly, so a hit returns bit for bit what computing it would. Whole-mesh
// passes (refresh) publish a new immutable snapshot; lookups take the current one under a mutex,
// so concurrent calls are safe and a pass never writes into a snapshot a reader holds. A miss
// hands the element's stored rotation (for other corners) to the computation as a warm start:
// between SQP iterates and time steps an element turns by little, and a polar decomposition
// iterated from the old rotation costs a fraction of a Jacobi SVD.
#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "sinew/core/svd.hpp"

namespace sinew {

// The polar decomposition F_tet = R S of the innermost tetrahedron's deformation gradient: R the
// rotation closest to F_tet (U V^T of its rotation-variant SVD), S = R^T F_tet (symmetric).
struct ElementRotation {
  Mat3 R;
  Mat3 S;
};

class ElementRotationCache {
 public:
  using Corners = std::array<double, 12>;
  // `corners(e, x)` gathers element e's 12 coordinates; `compute(e, corners, warm)` is its
  // rotation, `warm` the element's rotation at other corners (a starting guess) or null.
  using Gather = std::function<Corners(Eigen::Index e, const Eigen::VectorXd& x)>;
  using Compute = std::function<ElementRotation(Eigen::Index e, const Corners& corners, const ElementRotation* warm)>;

  explicit ElementRotationCache(Eigen::Index num_elements) : num_elements_(num_elements) {}

  // Every element's rotation at x (computed only where the stored one is for other corners),
  // stored for later lookups.
  std::shared_ptr<const std::vector<ElementRotation>> refresh(const Eigen::VectorXd& x, const Gather& corners,
                                                              const Compute& compute);
  // Element e's stored rotation: true if it was computed from these corners; false with `out`
  // the stored one for other corners (`*stale` set) or nothing stored (`*stale` cleared).
  bool lookup(Eigen::Index e, const Corners& corners, ElementRotation& out, bool* stale = nullptr) const;

 private:
  struct Snapshot {
    std::vector<Corners> corners;
    std::vector<ElementRotation> rotations;
  };
  Eigen::Index num_elements_;
  mutable std::mutex mutex_;
  std::shared_ptr<Snapshot> current_, spare_;  // spare_: the previous snapshot, reused when no one holds it
};

}  // namespace sinew
