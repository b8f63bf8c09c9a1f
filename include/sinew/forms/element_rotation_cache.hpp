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
// so concurrent calls are safe and a pass never writes into a snapshot a reader holds.
#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "sinew/core/svd.hpp"

namespace sinew {

struct ElementRotation {
  SignedSvd svd;  // F_tet = U diag(sigma) V^T
  Mat3 R;         // U V^T
};

class ElementRotationCache {
 public:
  using Corners = std::array<double, 12>;
  // `corners(e, x)` gathers element e's 12 coordinates; `compute(e, corners)` is its rotation.
  using Gather = std::function<Corners(Eigen::Index e, const Eigen::VectorXd& x)>;
  using Compute = std::function<ElementRotation(Eigen::Index e, const Corners& corners)>;

  explicit ElementRotationCache(Eigen::Index num_elements) : num_elements_(num_elements) {}

  // Every element's rotation at x (computed only where the stored one is for other corners),
  // stored for later lookups.
  std::shared_ptr<const std::vector<ElementRotation>> refresh(const Eigen::VectorXd& x, const Gather& corners,
                                                              const Compute& compute);
  // Element e's stored rotation if it was computed from these corners.
  bool lookup(Eigen::Index e, const Corners& corners, ElementRotation& out) const;

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
