#pragma once
// Where a quasistatic load step's Newton solve starts (docs/scene-format.md, solver.predictor).

namespace sinew {

enum class LoadStepPredictor {
  None,         // the previous state with only the prescribed DOFs moved
  Extrapolate,  // plus the last converged increment, scaled to the step's length
  // Plus the solution of the problem linearised at the previous state with the step's prescribed
  // increment and load change applied (engineering codes' first-increment predictor). Costs one
  // Hessian and one linear solve, so it pays where the prescribed motion would otherwise distort
  // the layer next to it (a lattice's first Newton steps crawl through that distortion).
  Tangent,
  Auto,  // Extrapolate when there is a last increment, Tangent otherwise (the first step)
};

}  // namespace sinew
