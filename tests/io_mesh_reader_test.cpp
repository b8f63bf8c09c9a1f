// Mesh readers: the checked-in small meshes in every format (node order, 1-based indices,
// positive rest volumes), and every error path with the file, line or array named.
#include <gtest/gtest.h>

#include "io_test_support.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/io/base64.hpp"
#include "sinew/io/mesh_reader.hpp"

namespace sinew {
namespace {

using test::data_path;
using test::error_message;
using test::expect_contains;
using test::TempDir;

double total_rest_volume(const VolumeMesh& mesh) {
  const Discretization disc(mesh, "test");
  double volume = 0.0;
  for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
    EXPECT_GT(disc.rest_volume(e), 0.0) << "element " << e;
    volume += disc.rest_volume(e);
  }
  return volume;
}

// Every file describing the 2 x 1 x 1 box must give these hexahedra (VTK order).
void expect_hex2(const VolumeMesh& mesh, bool same_numbering = true) {
  ASSERT_EQ(mesh.kind, ElementKind::Hex8);
  ASSERT_EQ(mesh.num_vertices(), 12);
  ASSERT_EQ(mesh.num_elements(), 2);
  EXPECT_NEAR(total_rest_volume(mesh), 2.0, 1e-14);
  // Element e spans [e, e+1] x [0,1] x [0,1]; node a sits at the VTK reference corner a.
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int e = 0; e < 2; ++e)
    for (int a = 0; a < 8; ++a) {
      const Eigen::RowVector3d expected(e + corner[a][0], corner[a][1], corner[a][2]);
      EXPECT_EQ(mesh.vertices.row(mesh.elements(e, a)), expected) << "element " << e << " node " << a;
    }
  if (same_numbering) {
    Eigen::MatrixXi expected(2, 8);
    expected << 0, 1, 4, 3, 6, 7, 10, 9, 1, 2, 5, 4, 7, 8, 11, 10;
    EXPECT_EQ(mesh.elements, expected);
  }
}

// The unit cube as five tetrahedra: corner tets {0,1,3,4}, {2,3,1,6}, {5,4,6,1}, {7,6,4,3}
// and the central {1,3,4,6} in cube-corner numbering.
void expect_tet5(const VolumeMesh& mesh) {
  ASSERT_EQ(mesh.kind, ElementKind::Tet4);
  ASSERT_EQ(mesh.num_vertices(), 8);
  ASSERT_EQ(mesh.num_elements(), 5);
  EXPECT_NEAR(total_rest_volume(mesh), 1.0, 1e-14);
  const double cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int tets[5][4] = {{0, 1, 3, 4}, {2, 3, 1, 6}, {5, 4, 6, 1}, {7, 6, 4, 3}, {1, 3, 4, 6}};
  for (int e = 0; e < 5; ++e)
    for (int a = 0; a < 4; ++a) {
      const double* c = cube[tets[e][a]];
      EXPECT_EQ(mesh.vertices.row(mesh.elements(e, a)), Eigen::RowVector3d(c[0], c[1], c[2]))
          << "element " << e << " node " << a;
    }
}

TEST(IoMeshReader, MeditHexahedra) { expect_hex2(read_volume_mesh(data_path("hex2.mesh"))); }

TEST(IoMeshReader, MeditTetrahedraWithOneBasedScrambledVertices) {
  const VolumeMesh mesh = read_volume_mesh(data_path("tet5.mesh"));
  expect_tet5(mesh);
  // File vertex 1 is the cube corner (1,1,1): 1-based indices map to row 0.
  EXPECT_EQ(mesh.vertices.row(0), Eigen::RowVector3d(1, 1, 1));
  EXPECT_EQ(mesh.elements(0, 0), 1);  // "2 5 3 8" -> 1 4 2 7
}

TEST(IoMeshReader, LegacyVtkOldAndNewCellLayouts) {
  expect_hex2(read_volume_mesh(data_path("hex2_v42.vtk")));
  expect_hex2(read_volume_mesh(data_path("hex2_v51.vtk")));
  expect_tet5(read_volume_mesh(data_path("tet5.vtk")));  // trailing POINT_DATA is ignored
}

TEST(IoMeshReader, VtuAsciiAndBinaryWrittenByVtk) {
  expect_hex2(read_volume_mesh(data_path("hex2_ascii.vtu")));   // InformationKey children inside arrays
  expect_hex2(read_volume_mesh(data_path("hex2_binary.vtu")));  // UInt32 headers
  expect_tet5(read_volume_mesh(data_path("tet5_uint64.vtu")));  // UInt64 headers
}

TEST(IoMeshReader, ExtensionIsCaseInsensitive) {
  TempDir dir;
  std::filesystem::copy_file(data_path("hex2.mesh"), dir / "HEX2.MESH");
  expect_hex2(read_volume_mesh(dir / "HEX2.MESH"));
}

TEST(IoMeshReader, LegacyVtk51MetadataBlocksAreSkipped) {
  TempDir dir;
  const auto path = dir.write("meta.vtk",
                              "# vtk DataFile Version 5.1\nmeta\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                              "POINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\n"
                              "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1\n\n"
                              "CELLS 2 4\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n0 1 2 3\n"
                              "CELL_TYPES 1\n10\n");
  const VolumeMesh mesh = read_volume_mesh(path);
  EXPECT_EQ(mesh.kind, ElementKind::Tet4);
  EXPECT_NEAR(total_rest_volume(mesh), 1.0 / 6.0, 1e-15);
}

TEST(IoMeshReader, VtuWithInt32AsciiArraysAndComments) {
  TempDir dir;
  const auto path = dir.write("t.vtu", R"(<?xml version="1.0"?>
<!-- hand written -->
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="BigEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="4" NumberOfCells="1">
      <Points>
        <DataArray type="Float32" NumberOfComponents="3" format="ascii">0 0 0  1 0 0  0 1 0  0 0 1</DataArray>
      </Points>
      <Cells>
        <DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>
        <DataArray type="Int32" Name="offsets" format="ascii">4</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">10</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)");
  const VolumeMesh mesh = read_volume_mesh(path);
  EXPECT_EQ(mesh.kind, ElementKind::Tet4);
  EXPECT_EQ(mesh.vertices.row(3), Eigen::RowVector3d(0, 0, 1));
}

struct BadFile {
  std::string name;
  std::string content;
  std::vector<std::string> expected;  // parts of the message, besides the file name
};

void expect_read_error(const TempDir& dir, const BadFile& bad) {
  const auto path = dir.write(bad.name, bad.content);
  const std::string message = error_message([&] { read_volume_mesh(path); });
  SCOPED_TRACE(bad.name);
  expect_contains(message, {bad.name.c_str()});
  for (const auto& part : bad.expected) expect_contains(message, {part.c_str()});
}

const std::string kHexVertices =
    "MeshVersionFormatted 1\nDimension 3\nVertices\n8\n0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n"
    "0 0 1 0\n1 0 1 0\n1 1 1 0\n0 1 1 0\n";

TEST(IoMeshReader, MeditErrors) {
  TempDir dir;
  const std::string v = kHexVertices;  // 12 lines: a following section starts on line 13
  const std::string tet = "Tetrahedra\n1\n1 2 4 5 0\n";
  const BadFile cases[] = {
      {"truncated.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n8\n0 0 0 0\n1 0", {":6", "end of file", "vertex coordinate"}},
      {"badnumber.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n1\n0 0x 0 0\n", {":5", "'0x'"}},
      {"range.mesh", (v + "Hexahedra\n1\n1 2 3 4 5 6 7 9 0\n"), {":15", "hexahedron 1 refers to vertex 9", "1 to 8"}},
      {"zero.mesh", (v + "Hexahedra\n1\n0 1 2 3 4 5 6 7 0\n"), {":15", "refers to vertex 0"}},
      {"mixed.mesh", (v + "Hexahedra\n1\n1 2 3 4 5 6 7 8 0\n" + tet), {"1 hexahedra and 1 tetrahedra", "mixing"}},
      {"keyword.mesh", (v + "Polygons\n1\n"), {":13", "unknown MEDIT keyword 'Polygons'"}},
      {"prisms.mesh", (v + "Prisms\n1\n1 2 3 4 5 6 0\n"), {":13", "Prisms are not supported"}},
      {"dim2.mesh", "MeshVersionFormatted 1\nDimension 2\n", {":2", "Dimension 2"}},
      {"noelements.mesh", v, {"no Hexahedra or Tetrahedra"}},
      {"inverted.mesh", (v + "Hexahedra\n1\n1 4 3 2 5 8 7 6 0\n"), {"element 0 is inverted"}},
      {"repeated.mesh", (v + "Tetrahedra\n1\n1 2 2 5 0\n"), {"repeats vertex 1"}},
      {"negcount.mesh", (v + "Hexahedra\n-1\n"), {":14", "count -1"}},
  };
  for (const auto& bad : cases) expect_read_error(dir, bad);
}

TEST(IoMeshReader, LegacyVtkErrors) {
  TempDir dir;
  const std::string head = "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n";
  const std::string points = head + "POINTS 4 float\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";  // ends on line 9
  const BadFile cases[] = {
      {"header.vtk", "hello\n", {":1", "not a legacy VTK file"}},
      {"binary.vtk", "# vtk DataFile Version 4.2\nt\nBINARY\n", {":3", "binary legacy VTK files are not supported"}},
      {"polydata.vtk", "# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\n", {":4", "DATASET POLYDATA"}},
      {"truncated.vtk", (head + "POINTS 4 float\n0 0 0\n1 0"), {":7", "end of file", "point coordinate"}},
      {"badnumber.vtk", (head + "POINTS 1 float\n0 zero 0\n"), {":6", "'zero'"}},
      {"celltype.vtk", (points + "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n"), {":13", "VTK type 5 (triangle)"}},
      {"range.vtk", (points + "CELLS 1 5\n4 0 1 2 4\nCELL_TYPES 1\n10\n"), {":11", "refers to point 4"}},
      {"nodes.vtk", (points + "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n10\n"), {":11", "with 3 nodes, expected 4"}},
      {"size.vtk", (points + "CELLS 1 6\n4 0 1 2 3\nCELL_TYPES 1\n10\n"), {"declares 6 numbers", "hold 5"}},
      {"mixed.vtk",
       (head + "POINTS 9 float\n0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1 2 0 0\n"
               "CELLS 2 14\n8 0 1 2 3 4 5 6 7\n4 1 8 2 5\nCELL_TYPES 2\n12\n10\n").c_str(),
       {":12", "cell 1 is a tetra", "mixing"}},
      {"nocells.vtk", points, {"no CELLS section"}},
      {"counts.vtk", (points + "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10\n10\n"), {"CELLS has 1 cells but CELL_TYPES has 2"}},
      {"keyword.vtk", (points + "LINES 1 3\n"), {":10", "unexpected keyword 'LINES'"}},
  };
  for (const auto& bad : cases) expect_read_error(dir, bad);
}

std::string vtu(const std::string& cells_xml, const std::string& root_extra = "",
                const std::string& points = "0 0 0 1 0 0 0 1 0 0 0 1", const std::string& format = "ascii") {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\"" +
         root_extra +
         ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">\n<Points>\n"
         "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"" + format + "\">" +
         points + "</DataArray>\n</Points>\n<Cells>\n" + cells_xml +
         "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

std::string cells(const std::string& connectivity, const std::string& offsets = "4", const std::string& types = "10") {
  return "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" + connectivity +
         "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">" + offsets +
         "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" + types + "</DataArray>\n";
}

TEST(IoMeshReader, VtuErrors) {
  TempDir dir;
  ASSERT_NO_THROW(read_volume_mesh(dir.write("good.vtu", vtu(cells("0 1 2 3")))));
  const std::string polydata = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"></VTKFile>\n";
  const std::string two_pieces =
      "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece/><Piece/></UnstructuredGrid></VTKFile>";
  const BadFile cases[] = {
      {"range.vtu", vtu(cells("0 1 2 4")), {"DataArray 'connectivity'", "refers to point 4"}},
      {"celltype.vtu", vtu(cells("0 1 2 3", "4", "9")), {"DataArray 'types'", "VTK type 9 (quad)"}},
      {"count.vtu", vtu(cells("0 1 2")), {"DataArray 'connectivity'", "has 3 values, expected 4"}},
      {"badnumber.vtu", vtu(cells("0 1 x 3")), {"DataArray 'connectivity'", "'x' is not an integer"}},
      {"floatcells.vtu",
       vtu("<DataArray type=\"Float64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>" +
           cells("").substr(cells("").find("<DataArray type=\"Int64\" Name=\"offsets\""))).c_str(),
       {"DataArray 'connectivity'", "integers are expected"}},
      {"nooffsets.vtu", vtu("<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 1 2 3</DataArray>").c_str(),
       {"no 'offsets' DataArray"}},
      {"truncated.vtu", vtu(cells("0 1 2 3")).substr(0, 200), {"end of file"}},
      {"unclosed.vtu", vtu(cells("0 1 2 3")).substr(0, 352), {":9", "<DataArray> is not closed"}},
      {"cut.vtu", vtu(cells("0 1 2 3")).substr(0, 360), {":9", "unexpected end of file in </DataA"}},
      {"mismatch.vtu", "<VTKFile type=\"UnstructuredGrid\">\n<UnstructuredGrid>\n</Piece>", {":3", "</Piece> closes <UnstructuredGrid>"}},
      {"polydata.vtu", polydata, {"type 'PolyData' is not supported"}},
      {"pieces.vtu", two_pieces, {"2 <Piece> elements"}},
      {"nan.vtu", vtu(cells("0 1 2 3"), "", "0 0 0 1 0 0 0 1 0 0 0 nan"), {"DataArray 'Points'", "value 11 is not finite"}},
      {"badbase64.vtu", vtu(cells("0 1 2 3"), "", "AAAA*AAA", "binary"), {"DataArray 'Points'", "not base64"}},
      {"header.vtu", vtu(cells("0 1 2 3"), "", "AQAAAAAA", "binary").c_str(),
       {"DataArray 'Points'", "size header says 1 bytes but 2 follow"}},
      {"short.vtu", vtu(cells("0 1 2 3"), "", "AQA=", "binary"), {"shorter than its size header"}},
      {"appendedarray.vtu", vtu(cells("0 1 2 3"), "", "", "appended"), {"appended data is not supported"}},
      {"format.vtu", vtu(cells("0 1 2 3"), "", "", "hex"), {"unknown format 'hex'"}},
      {"notxml.vtu", "hello", {"not an XML file"}},
  };
  for (const auto& bad : cases) expect_read_error(dir, bad);
  expect_read_error(dir, {"zlib.vtu", test::read_file(data_path("hex2_zlib.vtu")).c_str(),
                          {"DataArray 'Points'", "compressed data (vtkZLibDataCompressor) is not supported"}});
  expect_read_error(dir, {"appended.vtu", test::read_file(data_path("hex2_appended.vtu")).c_str(),
                          {"appended data", "not supported"}});
}

TEST(IoMeshReader, VtuBigEndianBinaryWithUInt64Header) {
  // A unit tetrahedron's points as big-endian Float64 after a big-endian UInt64 size header:
  // exercises the byte swapping on this little-endian machine.
  std::string raw;
  const auto put_big_endian = [&](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (std::size_t i = n; i-- > 0;) raw += static_cast<char>(b[i]);
  };
  const std::uint64_t size = 12 * sizeof(double);
  put_big_endian(&size, sizeof size);
  const double coords[12] = {0, 0, 0, 1.5, 0, 0, 0, 1, 0, 0, 0, 1};
  for (const double c : coords) put_big_endian(&c, sizeof c);
  std::string encoded;
  Base64Encoder encoder(encoded);
  encoder.append(raw.data(), raw.size());
  encoder.finish();
  std::string text = vtu(cells("0 1 2 3"), " header_type=\"UInt64\"", encoded, "binary");
  text.replace(text.find("LittleEndian"), 12, "BigEndian");
  TempDir dir;
  const VolumeMesh mesh = read_volume_mesh(dir.write("be.vtu", text));
  EXPECT_EQ(mesh.vertices.row(1), Eigen::RowVector3d(1.5, 0, 0));
  EXPECT_EQ(mesh.vertices.row(3), Eigen::RowVector3d(0, 0, 1));
}

TEST(IoMeshReader, FileAndExtensionErrors) {
  TempDir dir;
  expect_contains(error_message([&] { read_volume_mesh(dir / "absent.mesh"); }), {"absent.mesh", "does not exist"});
  std::filesystem::create_directory(dir / "folder.vtk");
  expect_contains(error_message([&] { read_volume_mesh(dir / "folder.vtk"); }), {"folder.vtk", "is a directory"});
  expect_contains(error_message([&] { read_volume_mesh(dir.write("m.obj", "v 0 0 0\n")); }),
                  {"m.obj", "unknown mesh file extension '.obj'", ".mesh", ".vtk", ".vtu"});
  expect_contains(error_message([&] { read_volume_mesh(dir.write("m.meshb", "")); }), {"m.meshb", "binary MEDIT"});
  expect_contains(error_message([&] { read_volume_mesh(dir.write("noext", "")); }), {"noext", "unknown mesh file extension ''"});
}

}  // namespace
}  // namespace sinew
