#include "sinew/mesh/inside_test.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <fmt/format.h>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Side = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;
}  // namespace

struct InsideTest::Impl {
  Mesh mesh;
  Tree tree;
  std::unique_ptr<Side> side;
  Eigen::AlignedBox3d bounds;
};

InsideTest::InsideTest(const TriangleSurface& surface) : impl_(std::make_unique<Impl>()) {
  surface.validate("inside test", true);
  impl_->bounds = surface.bounds();
  std::vector<Kernel::Point_3> points;
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v)
    points.emplace_back(surface.vertices(v, 0), surface.vertices(v, 1), surface.vertices(v, 2));
  std::vector<std::array<std::size_t, 3>> faces;
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f)
    faces.push_back({static_cast<std::size_t>(surface.faces(f, 0)), static_cast<std::size_t>(surface.faces(f, 1)),
                     static_cast<std::size_t>(surface.faces(f, 2))});
  // A halfedge mesh cannot hold an edge of four faces: orient_polygon_soup duplicates the points
  // of non-manifold edges and vertices, leaving separate closed sheets (same point set).
  namespace PMP = CGAL::Polygon_mesh_processing;
  PMP::orient_polygon_soup(points, faces);
  PMP::polygon_soup_to_polygon_mesh(points, faces, impl_->mesh);
  if (!CGAL::is_closed(impl_->mesh)) throw Error("surface is not closed after splitting non-manifold edges", "inside test");
  const auto faces_range = CGAL::faces(impl_->mesh);
  impl_->tree.insert(faces_range.first, faces_range.second, impl_->mesh);
  impl_->tree.build();
  impl_->side = std::make_unique<Side>(impl_->tree);
}

InsideTest::~InsideTest() = default;
InsideTest::InsideTest(InsideTest&&) noexcept = default;
InsideTest& InsideTest::operator=(InsideTest&&) noexcept = default;

bool InsideTest::inside(const Eigen::Vector3d& p) const {
  return (*impl_->side)(Kernel::Point_3(p.x(), p.y(), p.z())) != CGAL::ON_UNBOUNDED_SIDE;
}

bool InsideTest::intersects(const Eigen::AlignedBox3d& box) const {
  const CGAL::Bbox_3 b(box.min().x(), box.min().y(), box.min().z(), box.max().x(), box.max().y(), box.max().z());
  return impl_->tree.do_intersect(b);
}

const Eigen::AlignedBox3d& InsideTest::bounds() const { return impl_->bounds; }

}  // namespace sinew
