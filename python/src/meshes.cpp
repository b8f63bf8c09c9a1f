// sinew.Mesh (volume meshes: lattices, files, voxelised surfaces) and sinew.Surface (closed
// triangle surfaces).
#include <fmt/format.h>

#include "bindings.hpp"
#include "sinew/core/error.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/element/mesh_validation.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/io/vtk_writer.hpp"
#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/mesh/tetrahedralize_surface.hpp"
#include "sinew/mesh/voxelize.hpp"
#include "sinew/model/scene.hpp"

namespace sinew::python {
namespace {

using FloatArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IntArray = py::array_t<int, py::array::c_style | py::array::forcecast>;

// Read-only views of Eigen's column-major matrices: (rows, cols) with Fortran strides.
template <class Scalar>
py::array column_major_view(const Scalar* data, Eigen::Index rows, Eigen::Index cols, py::handle parent) {
  const auto s = static_cast<py::ssize_t>(sizeof(Scalar));
  return view(data, {rows, cols}, {s, s * rows}, parent);
}

Eigen::MatrixX3d vertices_from(const py::handle& object, const char* name) {
  const FloatArray a = FloatArray::ensure(object);
  if (!a || a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(fmt::format("{} must have shape (n, 3)", name));
  Eigen::MatrixX3d v(a.shape(0), 3);
  v = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(a.data(), a.shape(0), 3);
  return v;
}

Eigen::MatrixXi indices_from(const py::handle& object, py::ssize_t cols, const char* name) {
  const IntArray a = IntArray::ensure(object);
  if (!a || a.ndim() != 2 || (cols > 0 && a.shape(1) != cols))
    throw py::value_error(fmt::format("{} must have shape (n, {})", name, cols > 0 ? std::to_string(cols) : "k"));
  Eigen::MatrixXi e(a.shape(0), a.shape(1));
  e = Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(a.data(), a.shape(0),
                                                                                           a.shape(1));
  return e;
}

ElementKind kind_from(const std::string& text) {
  if (text == "hex") return ElementKind::Hex8;
  if (text == "tet") return ElementKind::Tet4;
  throw py::value_error(fmt::format("element kind must be 'hex' or 'tet', got '{}'", text));
}
const char* kind_name(ElementKind kind) { return kind == ElementKind::Hex8 ? "hex" : "tet"; }

using MeshPtr = std::shared_ptr<VolumeMesh>;
using SurfacePtr = std::shared_ptr<TriangleSurface>;

MeshPtr released(VolumeMesh mesh) { return std::make_shared<VolumeMesh>(std::move(mesh)); }

}  // namespace

void bind_meshes(py::module_& m) {
  py::class_<VolumeMesh, MeshPtr>(m, "Mesh", R"(A volume mesh of hexahedra (VTK_HEXAHEDRON node order) or tetrahedra: rest
positions and connectivity. vertices and elements are read-only views of the mesh's own arrays
(no copy; column-major, as Eigen stores them).)")
      .def(py::init([](const py::object& vertices, const py::object& elements, const std::optional<std::string>& kind) {
             auto mesh = std::make_shared<VolumeMesh>();
             mesh->vertices = vertices_from(vertices, "vertices");
             mesh->elements = indices_from(elements, 0, "elements");
             const Eigen::Index k = mesh->elements.cols();
             mesh->kind = kind ? kind_from(*kind) : (k == 4 ? ElementKind::Tet4 : ElementKind::Hex8);
             if (k != nodes_per_element(mesh->kind))
               throw py::value_error(fmt::format("elements of kind '{}' need {} columns, got {}", kind_name(mesh->kind),
                                                 nodes_per_element(mesh->kind), k));
             validate_mesh(*mesh, "mesh");
             return mesh;
           }),
           py::arg("vertices"), py::arg("elements"), py::arg("kind") = py::none(),
           "A mesh from arrays: vertices (n, 3), elements (m, 8) hexahedra or (m, 4) tetrahedra (0-based); "
           "validated like a mesh file (inverted or degenerate elements are a sinew.Error).")
      .def_static(
          "from_spec",
          [](const py::object& spec, const std::filesystem::path& path) {
            // The scene's own "mesh" reader and builder, so the keys and the checks are the scene's.
            nlohmann::json scene = {{"mesh", to_json(spec, "mesh")}, {"material", {{"family", "neo_hookean"}}}};
            const Scene s = parse_scene(scene, path);
            py::gil_scoped_release release;
            return released(build_scene_mesh(s));
          },
          py::arg("spec"), py::arg("path") = "mesh",
          "A mesh from a dict in the scene's \"mesh\" form (docs/scene-format.md): box, cylinder, sphere, "
          "voxels, file, surface (voxelised), tetrahedralize, with cells / cell_size / resolution, element. "
          "Relative file names are relative to `path`'s folder; errors name `path` and the field.")
      .def_property_readonly("vertices",
                             [](const py::object& self) {
                               const auto& mesh = self.cast<const VolumeMesh&>();
                               return column_major_view(mesh.vertices.data(), mesh.vertices.rows(), 3, self);
                             })
      .def_property_readonly("elements",
                             [](const py::object& self) {
                               const auto& mesh = self.cast<const VolumeMesh&>();
                               return column_major_view(mesh.elements.data(), mesh.elements.rows(),
                                                        mesh.elements.cols(), self);
                             })
      .def_property_readonly("kind", [](const VolumeMesh& mesh) { return kind_name(mesh.kind); })
      .def_property_readonly("num_vertices", &VolumeMesh::num_vertices)
      .def_property_readonly("num_elements", &VolumeMesh::num_elements)
      .def_property_readonly(
          "lattice",
          [](const VolumeMesh& mesh) -> py::object {
            if (!mesh.lattice) return py::none();
            const LatticeStructure& l = *mesh.lattice;
            return py::dict(py::arg("cells") = adopt(Eigen::VectorXi(l.cells), {3}),
                            py::arg("origin") = vector3(l.origin), py::arg("spacing") = vector3(l.spacing),
                            py::arg("vertex_point") = adopt(Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>(l.vertex_point),
                                                            {l.vertex_point.rows(), 3}),
                            py::arg("element_cell") = adopt(Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>(l.element_cell),
                                                            {l.element_cell.rows(), 3}),
                            py::arg("non_manifold") = l.non_manifold);
          },
          "The grid of a lattice (cells, origin, spacing, grid point per vertex, grid cell per element), "
          "or None for meshes read from files and for tetrahedra.")
      .def(
          "boundary",
          [](const VolumeMesh& mesh) {
            BoundarySurface s;
            {
              py::gil_scoped_release release;
              s = boundary_surface(mesh);
            }
            const int k = mesh.kind == ElementKind::Hex8 ? 4 : 3;
            Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> faces(s.faces.size(), k);
            for (size_t f = 0; f < s.faces.size(); ++f)
              for (int c = 0; c < k; ++c) faces(f, c) = s.faces[f][c];
            Eigen::VectorXi owner(s.face_element.size());
            for (size_t f = 0; f < s.face_element.size(); ++f) owner(f) = static_cast<int>(s.face_element[f]);
            const auto nf = static_cast<py::ssize_t>(s.faces.size());
            const auto nt = static_cast<py::ssize_t>(s.triangles.rows());
            Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> triangles = s.triangles;
            const auto nv = static_cast<py::ssize_t>(s.vertices.size());
            return py::dict(py::arg("faces") = adopt(std::move(faces), {nf, k}),
                            py::arg("face_element") = adopt(std::move(owner), {nf}),
                            py::arg("triangles") = adopt(std::move(triangles), {nt, 3}),
                            py::arg("vertices") = adopt(Eigen::Map<const Eigen::VectorXi>(s.vertices.data(), nv).eval(), {nv}));
          },
          "The boundary: faces (quads of hexahedra, triangles of tetrahedra; outward), the element of each "
          "face, the faces split into triangles, and the sorted boundary vertices.")
      .def(
          "rest_volumes",
          [](const MeshPtr& mesh) {
            Eigen::VectorXd v;
            {
              py::gil_scoped_release release;
              const Discretization d(*mesh, "mesh");
              v.resize(d.num_elements());
              for (Eigen::Index e = 0; e < d.num_elements(); ++e) v(e) = d.rest_volume(e);
            }
            const auto n = static_cast<py::ssize_t>(v.size());
            return adopt(std::move(v), {n});
          },
          "Each element's rest volume (by its quadrature rule).")
      .def(
          "to_tets",
          [](const VolumeMesh& mesh) {
            if (mesh.kind != ElementKind::Hex8) throw py::value_error("the mesh is already tetrahedral");
            py::gil_scoped_release release;
            return released(tetrahedralize_hexes(mesh));
          },
          "Each hexahedron split into six tetrahedra (the scene's \"element\": \"tet\").")
      .def(
          "write_vtu",
          [](const VolumeMesh& mesh, const std::filesystem::path& path, const py::object& positions, const py::dict& cell_fields,
             const py::dict& point_fields) {
            const Eigen::VectorXd x = positions.is_none()
                                          ? mesh.rest_positions()
                                          : positions_vector(FloatArray::ensure(positions), mesh.num_vertices(), "positions");
            VtuFields fields;
            for (auto item : cell_fields) {
              const FloatArray a = FloatArray::ensure(item.second);
              if (!a || a.ndim() != 1 || a.shape(0) != mesh.num_elements())
                throw py::value_error(fmt::format("cell field '{}' must have shape ({},)", std::string(py::str(item.first)),
                                                  mesh.num_elements()));
              fields.cell_scalars.emplace_back(py::str(item.first), Eigen::Map<const Eigen::VectorXd>(a.data(), a.size()));
            }
            for (auto item : point_fields) {
              const FloatArray a = FloatArray::ensure(item.second);
              const std::string name = py::str(item.first);
              if (a && a.ndim() == 1 && a.shape(0) == mesh.num_vertices())
                fields.point_scalars.emplace_back(name, Eigen::Map<const Eigen::VectorXd>(a.data(), a.size()));
              else
                fields.point_vectors.emplace_back(name, positions_vector(a, mesh.num_vertices(), name.c_str()));
            }
            py::gil_scoped_release release;
            write_vtu(path, mesh, x, fields);
          },
          py::arg("path"), py::arg("positions") = py::none(), py::arg("cell_fields") = py::dict(),
          py::arg("point_fields") = py::dict(),
          "Writes a VTU file (ParaView) of the mesh at `positions` (n, 3; default the rest positions) with "
          "per-element scalars and per-vertex scalars (n,) or vectors (n, 3).")
      .def("__repr__", [](const VolumeMesh& mesh) {
        return fmt::format("<sinew.Mesh {} vertices, {} {} elements>", mesh.num_vertices(), mesh.num_elements(),
                           kind_name(mesh.kind));
      });

  m.def(
      "read_mesh",
      [](const std::filesystem::path& path, bool reorient) {
        py::gil_scoped_release release;
        return released(read_volume_mesh(path, {reorient}));
      },
      py::arg("path"), py::arg("reorient") = false,
      "Reads a volume mesh: MEDIT .mesh, VTK .vtk / .vtu, Gmsh .msh, TetGen .node/.ele "
      "(docs/file-formats.md); `reorient` renumbers inverted elements instead of rejecting them.");

  py::class_<TriangleSurface, SurfacePtr>(m, "Surface", R"(A triangle surface (what voxelisation and tetrahedralisation take).
vertices and faces are read-only views of its own arrays.)")
      .def(py::init([](const py::object& vertices, const py::object& faces, bool closed) {
             auto s = std::make_shared<TriangleSurface>();
             s->vertices = vertices_from(vertices, "vertices");
             s->faces = indices_from(faces, 3, "faces");
             s->validate("surface", closed);
             return s;
           }),
           py::arg("vertices"), py::arg("faces"), py::arg("closed") = true,
           "A surface from arrays: vertices (n, 3), faces (m, 3), counter-clockwise seen from outside; "
           "validated (closed, consistently oriented, enclosing positive volume unless closed=False).")
      .def_property_readonly("vertices",
                             [](const py::object& self) {
                               const auto& s = self.cast<const TriangleSurface&>();
                               return column_major_view(s.vertices.data(), s.vertices.rows(), 3, self);
                             })
      .def_property_readonly("faces",
                             [](const py::object& self) {
                               const auto& s = self.cast<const TriangleSurface&>();
                               return column_major_view(s.faces.data(), s.faces.rows(), 3, self);
                             })
      .def_property_readonly("volume", &TriangleSurface::volume)
      .def_property_readonly("bounds",
                             [](const TriangleSurface& s) {
                               const auto b = s.bounds();
                               return py::make_tuple(vector3(b.min()), vector3(b.max()));
                             })
      .def("__repr__", [](const TriangleSurface& s) {
        return fmt::format("<sinew.Surface {} vertices, {} triangles>", s.num_vertices(), s.num_faces());
      });

  m.def(
      "read_surface",
      [](const std::filesystem::path& path, bool closed) {
        py::gil_scoped_release release;
        return std::make_shared<TriangleSurface>(read_triangle_surface(path, closed));
      },
      py::arg("path"), py::arg("closed") = true,
      "Reads a triangle surface: OBJ, STL, PLY or OFF (polygons split into triangles).");

  m.def(
      "voxelize",
      [](const TriangleSurface& surface, std::optional<double> cell_size, std::optional<int> resolution,
         bool non_manifold, bool keep_crossing, const py::object& grid_origin) {
        VoxelizeOptions o;
        o.cell_size = cell_size;
        o.resolution = resolution;
        o.non_manifold = non_manifold;
        o.keep_crossing = keep_crossing;
        if (!grid_origin.is_none()) o.grid_origin = to_vector3(grid_origin, "grid_origin");
        py::gil_scoped_release release;
        const InsideTest inside(surface);
        return released(voxelize_surface(inside, o));
      },
      py::arg("surface"), py::arg("cell_size") = py::none(), py::arg("resolution") = py::none(),
      py::arg("non_manifold") = false, py::arg("keep_crossing") = true, py::arg("grid_origin") = py::none(),
      "A hexahedral lattice covering a closed surface (docs/surfaces.md): exactly one of cell_size or "
      "resolution (cells along the longest side); non_manifold gives parts touching only along an edge or "
      "at a vertex their own vertices.");

  m.def(
      "tetrahedralize",
      [](const TriangleSurface& surface, double max_edge) {
        py::gil_scoped_release release;
        return released(tetrahedralize_surface(surface, max_edge));
      },
      py::arg("surface"), py::arg("max_edge"),
      "Tetrahedra filling a closed surface (Gmsh), edges at most about max_edge long.");
}

}  // namespace sinew::python
