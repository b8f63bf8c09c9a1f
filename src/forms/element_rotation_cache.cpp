#include "sinew/forms/element_rotation_cache.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sinew {

std::shared_ptr<const std::vector<ElementRotation>> ElementRotationCache::refresh(const Eigen::VectorXd& x,
                                                                                    const Gather& corners,
                                                                                    const Compute& compute) {
  std::shared_ptr<const Snapshot> old;
  std::shared_ptr<Snapshot> next;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    old = current_;
    next = std::move(spare_);
  }
  // The spare is written in place only when no reader still holds it (it is unpublished, so
  // none can take it meanwhile).
  if (!next || next.use_count() > 1) next = std::make_shared<Snapshot>();
  next->corners.resize(static_cast<size_t>(num_elements_));
  next->rotations.resize(static_cast<size_t>(num_elements_));
  // An element costs about a microsecond: small meshes stay on one thread.
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, num_elements_, 128), [&](const auto& range) {
    for (Eigen::Index e = range.begin(); e < range.end(); ++e) {
      const auto i = static_cast<size_t>(e);
      next->corners[i] = corners(e, x);
      if (old && old->corners[i] == next->corners[i])
        next->rotations[i] = old->rotations[i];
      else
        next->rotations[i] = compute(e, next->corners[i], old ? &old->rotations[i] : nullptr);
    }
  });
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    spare_ = std::move(current_);
    current_ = next;
  }
  return {next, &next->rotations};
}

bool ElementRotationCache::lookup(Eigen::Index e, const Corners& corners, ElementRotation& out, bool* stale) const {
  std::shared_ptr<const Snapshot> snapshot;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    snapshot = current_;
  }
  const auto i = static_cast<size_t>(e);
  if (stale) *stale = false;
  if (!snapshot) return false;
  out = snapshot->rotations[i];
  if (snapshot->corners[i] == corners) return true;
  if (stale) *stale = true;
  return false;
}

}  // namespace sinew
