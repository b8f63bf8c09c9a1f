#include "sinew/io/vtk_writer.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <limits>
#include <ostream>
#include <set>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/base64.hpp"

namespace sinew {
namespace {

constexpr const char* kByteOrder =
    std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";

// The XML prologue up to an UnstructuredGrid's <Piece>: version 0.1 with a UInt32 header_type is
// what VTK itself writes for 32-bit headers.
void write_piece_header(std::ostream& os, Eigen::Index points, Eigen::Index cells) {
  os << "<?xml version=\"1.0\"?>\n"
     << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"" << kByteOrder
     << "\" header_type=\"UInt32\">\n"
     << "  <UnstructuredGrid>\n"
     << fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", points, cells);
}

// VTK cell type ids (vtkCellType.h).
constexpr std::uint8_t kTetraType = 10;
constexpr std::uint8_t kHexahedronType = 12;

// One <DataArray format="binary">: base64 of [UInt32 byte count][raw values] as a single
// stream, which is how VTK itself writes uncompressed inline arrays.
void write_array(std::ostream& os, std::string& scratch, const std::string& name, const char* type,
                 int components, const void* data, std::size_t bytes) {
  if (bytes > std::numeric_limits<std::uint32_t>::max()) {
    throw Error(fmt::format("array '{}' has {} bytes, over the 4 GiB a UInt32 header can describe",
                            name, bytes));
  }
  const auto header = static_cast<std::uint32_t>(bytes);
  scratch.clear();
  scratch.reserve((sizeof header + bytes + 2) / 3 * 4);
  Base64Encoder encoder(scratch);
  encoder.append(&header, sizeof header);
  encoder.append(data, bytes);
  encoder.finish();
  os << fmt::format("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"binary\">\n          ",
                    type, xml_escape(name), components);
  os.write(scratch.data(), static_cast<std::streamsize>(scratch.size()));
  os << "\n        </DataArray>\n";
}

void write_doubles(std::ostream& os, std::string& scratch, const std::string& name, int components,
                   const Eigen::VectorXd& values) {
  write_array(os, scratch, name, "Float64", components, values.data(),
              static_cast<std::size_t>(values.size()) * sizeof(double));
}

void check_fields(const std::vector<std::pair<std::string, Eigen::VectorXd>>& fields,
                  Eigen::Index expected, const char* what, std::set<std::string>& names) {
  for (const auto& [name, values] : fields) {
    if (name.empty()) throw Error(fmt::format("a {} array has an empty name", what));
    if (!names.insert(name).second) {
      throw Error(fmt::format("{} array name '{}' is used twice (or is reserved)", what, name));
    }
    if (values.size() != expected) {
      throw Error(fmt::format("{} array '{}' has {} values, expected {}", what, name, values.size(),
                              expected));
    }
  }
}

void check_arrays(const std::vector<VtuArray>& arrays, Eigen::Index entities, const char* what,
                  std::set<std::string>& names) {
  for (const VtuArray& a : arrays) {
    if (a.name.empty()) throw Error(fmt::format("a {} array has an empty name", what));
    if (!names.insert(a.name).second) throw Error(fmt::format("{} array name '{}' is used twice (or is reserved)", what, a.name));
    if (a.components < 1) throw Error(fmt::format("{} array '{}' has {} components", what, a.name, a.components));
    if (a.values.size() != a.components * entities) {
      throw Error(fmt::format("{} array '{}' has {} values, expected {} x {}", what, a.name, a.values.size(),
                              a.components, entities));
    }
  }
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

void write_vtu(const std::filesystem::path& path, const VolumeMesh& mesh, const Eigen::VectorXd& x,
               const VtuFields& fields) {
  const Eigen::Index nv = mesh.num_vertices(), ne = mesh.num_elements();
  const int nodes = nodes_per_element(mesh.kind);
  try {
    if (mesh.elements.cols() != nodes) {
      throw Error(fmt::format("{} mesh has {} columns of element nodes, expected {}",
                              to_string(mesh.kind), mesh.elements.cols(), nodes));
    }
    if (x.size() != 3 * nv) {
      throw Error(fmt::format("positions have {} values, expected 3 x {} vertices", x.size(), nv));
    }
    std::set<std::string> point_names{"displacement"}, cell_names;
    check_fields(fields.point_vectors, 3 * nv, "point vector", point_names);
    check_fields(fields.point_scalars, nv, "point scalar", point_names);
    check_fields(fields.cell_scalars, ne, "cell scalar", cell_names);
    check_arrays(fields.point_arrays, nv, "point", point_names);
    check_arrays(fields.cell_arrays, ne, "cell", cell_names);
  } catch (const Error& e) {
    throw e.within(path.string());
  }

  write_file_atomically(path, [&](std::ostream& os) {
    std::string scratch;
    write_piece_header(os, nv, ne);

    os << "      <PointData Vectors=\"displacement\">\n";
    const Eigen::VectorXd displacement = x - mesh.rest_positions();
    write_doubles(os, scratch, "displacement", 3, displacement);
    for (const auto& [name, values] : fields.point_vectors) write_doubles(os, scratch, name, 3, values);
    for (const auto& [name, values] : fields.point_scalars) write_doubles(os, scratch, name, 1, values);
    for (const VtuArray& a : fields.point_arrays) write_doubles(os, scratch, a.name, a.components, a.values);
    os << "      </PointData>\n";

    if (fields.cell_scalars.empty()) {
      os << "      <CellData>\n";
    } else {
      os << "      <CellData Scalars=\"" << xml_escape(fields.cell_scalars.front().first) << "\">\n";
    }
    for (const auto& [name, values] : fields.cell_scalars) write_doubles(os, scratch, name, 1, values);
    for (const VtuArray& a : fields.cell_arrays) write_doubles(os, scratch, a.name, a.components, a.values);
    os << "      </CellData>\n";

    os << "      <Points>\n";
    write_doubles(os, scratch, "Points", 3, x);
    os << "      </Points>\n";

    os << "      <Cells>\n";
    {
      // Row-major node lists; Eigen stores elements column-major.
      std::vector<std::int64_t> connectivity(static_cast<std::size_t>(ne * nodes));
      for (Eigen::Index e = 0; e < ne; ++e)
        for (int a = 0; a < nodes; ++a) connectivity[static_cast<std::size_t>(e * nodes + a)] = mesh.elements(e, a);
      write_array(os, scratch, "connectivity", "Int64", 1, connectivity.data(),
                  connectivity.size() * sizeof(std::int64_t));
    }
    {
      std::vector<std::int64_t> offsets(static_cast<std::size_t>(ne));
      for (Eigen::Index e = 0; e < ne; ++e) offsets[static_cast<std::size_t>(e)] = (e + 1) * nodes;
      write_array(os, scratch, "offsets", "Int64", 1, offsets.data(), offsets.size() * sizeof(std::int64_t));
    }
    {
      const std::vector<std::uint8_t> types(static_cast<std::size_t>(ne),
                                            mesh.kind == ElementKind::Hex8 ? kHexahedronType : kTetraType);
      write_array(os, scratch, "types", "UInt8", 1, types.data(), types.size());
    }
    os << "      </Cells>\n"
       << "    </Piece>\n"
       << "  </UnstructuredGrid>\n"
       << "</VTKFile>\n";
  });
}

namespace {

// Polygon cells: face f is corners [start[f], start[f + 1]) of `corners`.
void write_polygon_cells_vtu(const std::filesystem::path& path, const Eigen::MatrixX3d& positions,
                             const std::vector<int>& start, const std::vector<int>& corners) {
  const Eigen::Index nv = positions.rows();
  const auto nf = static_cast<Eigen::Index>(start.size()) - 1;
  for (Eigen::Index f = 0; f < nf; ++f) {
    if (start[f + 1] - start[f] < 3) throw Error(fmt::format("face {} has fewer than 3 corners", f), path.string());
    for (int c = start[f]; c < start[f + 1]; ++c)
      if (corners[c] < 0 || corners[c] >= nv)
        throw Error(fmt::format("face {} refers to vertex {} (there are {})", f, corners[c], nv), path.string());
  }
  write_file_atomically(path, [&](std::ostream& os) {
    std::string scratch;
    write_piece_header(os, nv, nf);
    os << "      <Points>\n";
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> rows = positions;
    write_array(os, scratch, "Points", "Float64", 3, rows.data(), static_cast<std::size_t>(rows.size()) * sizeof(double));
    os << "      </Points>\n      <Cells>\n";
    const std::vector<std::int64_t> connectivity(corners.begin(), corners.end());
    write_array(os, scratch, "connectivity", "Int64", 1, connectivity.data(), connectivity.size() * sizeof(std::int64_t));
    const std::vector<std::int64_t> offsets(start.begin() + 1, start.end());
    write_array(os, scratch, "offsets", "Int64", 1, offsets.data(), offsets.size() * sizeof(std::int64_t));
    std::vector<std::uint8_t> types(static_cast<std::size_t>(nf));
    for (Eigen::Index f = 0; f < nf; ++f) {
      const int n = start[f + 1] - start[f];
      types[static_cast<std::size_t>(f)] = n == 3 ? 5 : n == 4 ? 9 : 7;  // VTK_TRIANGLE, VTK_QUAD, VTK_POLYGON
    }
    write_array(os, scratch, "types", "UInt8", 1, types.data(), types.size());
    os << "      </Cells>\n"
       << "    </Piece>\n"
       << "  </UnstructuredGrid>\n"
       << "</VTKFile>\n";
  });
}

}  // namespace

void write_surface_vtu(const std::filesystem::path& path, const PolygonSurface& surface,
                       const Eigen::MatrixX3d& positions) {
  surface.validate(path.string());
  if (positions.rows() != surface.num_positions())
    throw Error(fmt::format("{} positions given for a surface of {} vertices", positions.rows(), surface.num_positions()),
                path.string());
  std::vector<int> corners;
  for (const auto& c : surface.corners) corners.push_back(c.position);
  write_polygon_cells_vtu(path, positions, surface.face_start, corners);
}

void write_surface_vtu(const std::filesystem::path& path, const TriangleSurface& surface) {
  std::vector<int> start(static_cast<std::size_t>(surface.faces.rows()) + 1), corners;
  for (Eigen::Index t = 0; t < surface.faces.rows(); ++t) {
    start[static_cast<std::size_t>(t + 1)] = static_cast<int>(3 * (t + 1));
    for (int k = 0; k < 3; ++k) corners.push_back(surface.faces(t, k));
  }
  write_polygon_cells_vtu(path, surface.vertices, start, corners);
}

void write_pvd(const std::filesystem::path& path,
               const std::vector<std::pair<double, std::string>>& time_and_relative_file, PvdTime meaning) {
  for (std::size_t i = 0; i < time_and_relative_file.size(); ++i) {
    const auto& [time, file] = time_and_relative_file[i];
    if (!std::isfinite(time)) {
      throw Error(fmt::format("data set {} ('{}') has a non-finite time", i, file), path.string());
    }
    if (file.empty()) throw Error(fmt::format("data set {} has an empty file name", i), path.string());
  }
  write_file_atomically(path, [&](std::ostream& os) {
    os << "<?xml version=\"1.0\"?>\n"
       << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"" << kByteOrder << "\">\n";
    if (meaning == PvdTime::Seconds) os << "  <!-- timestep: simulated time in seconds (dynamic run) -->\n";
    if (meaning == PvdTime::Frames)
      os << "  <!-- timestep: frame number (quasistatic run: frames are load steps, not time) -->\n";
    os << "  <Collection>\n";
    for (const auto& [time, file] : time_and_relative_file) {
      // {} prints the shortest decimal that reads back to the same double.
      os << fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", time,
                        xml_escape(file));
    }
    os << "  </Collection>\n"
       << "</VTKFile>\n";
  });
}

}  // namespace sinew
