// Output writers: .vtu contents decoded by hand and read back by our reader, .pvd and .obj
// text, and argument checks that leave no file behind.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstring>
#include <regex>
#include <sstream>
#include <algorithm>
#include <cmath>

#include "io_test_support.hpp"
#include "sinew/io/base64.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/obj_writer.hpp"
#include "sinew/io/vtk_writer.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/surface.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;
using test::read_file;
using test::TempDir;

// A smooth deformation (stretch, shear, twist) of the rest positions.
Eigen::VectorXd deform(const VolumeMesh& mesh) {
  Eigen::VectorXd x = mesh.rest_positions();
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d p = mesh.vertices.row(v).transpose();
    x.segment<3>(3 * v) = Eigen::Vector3d(1.2 * p.x() + 0.1 * p.z(), p.y() + 0.05 * std::sin(p.x()), 0.9 * p.z() + 0.3);
  }
  return x;
}

// The decoded bytes (after the UInt32 header) of the DataArray called `name`.
std::vector<unsigned char> array_bytes(const std::string& text, const std::string& name) {
  const std::regex pattern("<DataArray [^>]*Name=\"" + name + "\"[^>]*format=\"binary\">\\s*([A-Za-z0-9+/=]+)\\s*</DataArray>");
  std::smatch m;
  if (!std::regex_search(text, m, pattern)) {
    ADD_FAILURE() << "no binary DataArray " << name;
    return {};
  }
  auto bytes = base64_decode(m[1].str());
  std::uint32_t header = 0;
  std::memcpy(&header, bytes.data(), 4);
  EXPECT_EQ(header, bytes.size() - 4) << name;
  return std::vector<unsigned char>(bytes.begin() + 4, bytes.end());
}

template <class T>
std::vector<T> array_values(const std::string& text, const std::string& name) {
  const auto bytes = array_bytes(text, name);
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

TEST(IoVtkWriter, VtuHoldsDeformedPointsDisplacementFieldsAndCells) {
  TempDir dir;
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 1, 1), Eigen::Vector3i(2, 1, 1));
  const Eigen::VectorXd x = deform(mesh);
  VtuFields fields;
  Eigen::VectorXd velocity = Eigen::VectorXd::LinSpaced(x.size(), -1.0, 1.0);
  Eigen::VectorXd J(2), energy(2), pinned = Eigen::VectorXd::Zero(mesh.num_vertices());
  J << 1.08, 0.97;
  energy << 0.25, 1e-300;
  pinned[3] = 1.0;
  fields.point_vectors.emplace_back("velocity", velocity);
  fields.point_scalars.emplace_back("pinned", pinned);
  fields.cell_scalars.emplace_back("J", J);
  fields.cell_scalars.emplace_back("energy", energy);
  const auto path = dir / "frame.vtu";
  write_vtu(path, mesh, x, fields);
  const std::string text = read_file(path);

  expect_contains(text, {"<VTKFile type=\"UnstructuredGrid\"", "header_type=\"UInt32\"",
                         "NumberOfPoints=\"12\" NumberOfCells=\"2\"", "<PointData Vectors=\"displacement\">",
                         "<CellData Scalars=\"J\">", "type=\"Int64\" Name=\"connectivity\"",
                         "type=\"UInt8\" Name=\"types\""});
  const auto points = array_values<double>(text, "Points");
  ASSERT_EQ(points.size(), static_cast<std::size_t>(x.size()));
  for (Eigen::Index i = 0; i < x.size(); ++i) EXPECT_EQ(points[static_cast<std::size_t>(i)], x[i]);
  const auto displacement = array_values<double>(text, "displacement");
  const Eigen::VectorXd expected_u = x - mesh.rest_positions();
  ASSERT_EQ(displacement.size(), static_cast<std::size_t>(x.size()));
  for (Eigen::Index i = 0; i < x.size(); ++i) EXPECT_EQ(displacement[static_cast<std::size_t>(i)], expected_u[i]);
  EXPECT_EQ(array_values<double>(text, "velocity")[5], velocity[5]);
  EXPECT_EQ(array_values<double>(text, "pinned")[3], 1.0);
  EXPECT_EQ(array_values<double>(text, "J"), (std::vector<double>{1.08, 0.97}));
  EXPECT_EQ(array_values<double>(text, "energy"), (std::vector<double>{0.25, 1e-300}));
  const auto connectivity = array_values<std::int64_t>(text, "connectivity");
  ASSERT_EQ(connectivity.size(), 16u);
  for (int e = 0; e < 2; ++e)
    for (int a = 0; a < 8; ++a) EXPECT_EQ(connectivity[static_cast<std::size_t>(8 * e + a)], mesh.elements(e, a));
  EXPECT_EQ(array_values<std::int64_t>(text, "offsets"), (std::vector<std::int64_t>{8, 16}));
  EXPECT_EQ(array_bytes(text, "types"), (std::vector<unsigned char>{12, 12}));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"frame.vtu"});
}

TEST(IoVtkWriter, VtuRoundTripsThroughTheReader) {
  TempDir dir;
  for (const bool tets : {false, true}) {
    VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3), Eigen::Vector3i(2, 3, 4));
    if (tets) mesh = tetrahedralize_hexes(mesh);
    const Eigen::VectorXd x = deform(mesh);
    const auto path = dir / (tets ? "tets.vtu" : "hexes.vtu");
    write_vtu(path, mesh, x);
    const VolumeMesh back = read_volume_mesh(path);
    EXPECT_EQ(back.kind, mesh.kind);
    ASSERT_EQ(back.num_vertices(), mesh.num_vertices());
    EXPECT_EQ(back.rest_positions(), x);  // bit-exact: binary Float64
    EXPECT_EQ(back.elements, mesh.elements);
  }
}

TEST(IoVtkWriter, OutputIsDeterministic) {
  TempDir dir;
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(3, 3, 3));
  const Eigen::VectorXd x = deform(mesh);
  write_vtu(dir / "a.vtu", mesh, x);
  write_vtu(dir / "b.vtu", mesh, x);
  EXPECT_EQ(read_file(dir / "a.vtu"), read_file(dir / "b.vtu"));
}

TEST(IoVtkWriter, VtuArgumentErrorsNameTheArrayAndWriteNothing) {
  TempDir dir;
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(1, 1, 1));
  const Eigen::VectorXd x = mesh.rest_positions();
  const auto path = dir / "bad.vtu";
  expect_contains(error_message([&] { write_vtu(path, mesh, Eigen::VectorXd::Zero(5)); }),
                  {"bad.vtu", "positions have 5 values"});
  VtuFields short_cells;
  short_cells.cell_scalars.emplace_back("J", Eigen::VectorXd::Ones(3));
  expect_contains(error_message([&] { write_vtu(path, mesh, x, short_cells); }),
                  {"bad.vtu", "cell scalar array 'J' has 3 values, expected 1"});
  VtuFields reserved;
  reserved.point_vectors.emplace_back("displacement", x);
  expect_contains(error_message([&] { write_vtu(path, mesh, x, reserved); }), {"'displacement'", "used twice"});
  VtuFields unnamed;
  unnamed.point_scalars.emplace_back("", Eigen::VectorXd::Zero(8));
  expect_contains(error_message([&] { write_vtu(path, mesh, x, unnamed); }), {"empty name"});
  expect_contains(error_message([&] { write_vtu(dir / "no" / "such.vtu", mesh, x); }), {"such.vtu", "does not exist"});
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoVtkWriter, FieldNamesAreEscaped) {
  TempDir dir;
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(1, 1, 1));
  VtuFields fields;
  fields.cell_scalars.emplace_back("a<b & \"c\"", Eigen::VectorXd::Ones(1));
  write_vtu(dir / "f.vtu", mesh, mesh.rest_positions(), fields);
  expect_contains(read_file(dir / "f.vtu"), {"Name=\"a&lt;b &amp; &quot;c&quot;\""});
}

TEST(IoVtkWriter, PvdListsTimesAndFiles) {
  TempDir dir;
  write_pvd(dir / "run.pvd", {{0.0, "frames/f0.vtu"}, {0.1, "frames/f1.vtu"}, {1.0 / 3.0, "a&b.vtu"}});
  const std::string text = read_file(dir / "run.pvd");
  expect_contains(text, {"<VTKFile type=\"Collection\"", "<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"frames/f0.vtu\"/>",
                         "timestep=\"0.1\"", "timestep=\"0.3333333333333333\"", "file=\"a&amp;b.vtu\"", "</Collection>"});
  expect_contains(error_message([&] { write_pvd(dir / "bad.pvd", {{std::nan(""), "x.vtu"}}); }),
                  {"bad.pvd", "non-finite time"});
  expect_contains(error_message([&] { write_pvd(dir / "bad.pvd", {{0.0, ""}}); }), {"empty file name"});
}

TEST(IoObjWriter, WritesOneBasedFacesAndExactCoordinates) {
  TempDir dir;
  Eigen::MatrixX3d v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0.1, 1.0 / 3.0, -2.5e-7;
  Eigen::MatrixXi t(1, 3);
  t << 0, 1, 2;
  write_obj(dir / "tri.obj", v, t);
  EXPECT_EQ(read_file(dir / "tri.obj"), "v 0 0 0\nv 1 0 0\nv 0.1 0.3333333333333333 -2.5e-07\nf 1 2 3\n");
  t(0, 2) = 3;
  expect_contains(error_message([&] { write_obj(dir / "bad.obj", v, t); }),
                  {"bad.obj", "triangle 0 refers to vertex 3"});
}

TEST(IoObjWriter, SurfaceObjHasOnlyBoundaryVerticesAtDeformedPositions) {
  TempDir dir;
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(3, 3, 3));
  const BoundarySurface surface = boundary_surface(mesh);
  const Eigen::VectorXd x = deform(mesh);
  write_surface_obj(dir / "s.obj", mesh, surface, x);
  const std::string text = read_file(dir / "s.obj");
  // 64 lattice vertices, 8 interior ones are left out; 6 faces x 9 quads x 2 triangles.
  std::size_t vertex_lines = 0, face_lines = 0;
  std::istringstream lines(text);
  std::vector<Eigen::Vector3d> read_vertices;
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      Eigen::Vector3d p;
      fields >> p.x() >> p.y() >> p.z();
      read_vertices.push_back(p);
      ++vertex_lines;
    } else if (tag == "f") {
      int a, b, c;
      fields >> a >> b >> c;
      EXPECT_GE(std::min({a, b, c}), 1);
      EXPECT_LE(std::max({a, b, c}), 56);
      ++face_lines;
    }
  }
  EXPECT_EQ(vertex_lines, 56u);
  EXPECT_EQ(face_lines, 108u);
  ASSERT_EQ(read_vertices.size(), surface.vertices.size());
  for (std::size_t i = 0; i < surface.vertices.size(); ++i) {
    EXPECT_EQ(read_vertices[i], x.segment<3>(3 * surface.vertices[i]));  // shortest round-trip text
  }
  expect_contains(error_message([&] { write_surface_obj(dir / "bad.obj", mesh, surface, Eigen::VectorXd::Zero(3)); }),
                  {"bad.obj", "positions have 3 values"});
}

}  // namespace
}  // namespace sinew
