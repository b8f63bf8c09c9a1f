#pragma once
// Point-in-closed-surface and box-meets-surface queries, built once from a closed triangle
// surface and then asked many times (voxelisation asks once or twice per lattice cell).
// Backed by CGAL: an AABB tree over the faces and Side_of_triangle_mesh, whose ray casting
// uses exact predicates, so points near edges and vertices are classified consistently.
#include <Eigen/Geometry>
#include <memory>

#include "sinew/mesh/triangle_surface.hpp"

namespace sinew {

class InsideTest {
 public:
  // `surface` must be closed (TriangleSurface::validate); throws a sinew::Error otherwise.
  // Edges shared by four faces (solids touching along an edge) are allowed.
  explicit InsideTest(const TriangleSurface& surface);
  ~InsideTest();
  InsideTest(InsideTest&&) noexcept;
  InsideTest& operator=(InsideTest&&) noexcept;
  InsideTest(const InsideTest&) = delete;
  InsideTest& operator=(const InsideTest&) = delete;

  // Inside or on the surface.
  bool inside(const Eigen::Vector3d& p) const;
  // Whether the closed box meets a face of the surface.
  bool intersects(const Eigen::AlignedBox3d& box) const;
  const Eigen::AlignedBox3d& bounds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sinew
