// Legacy VTK ASCII files ("# vtk DataFile Version x.y"), DATASET UNSTRUCTURED_GRID:
//   POINTS n type          n x 3 numbers
//   CELLS n size           up to 4.2: n lists "k i_1 ... i_k" (size = total numbers)
//   CELLS n+1 m            5.1: OFFSETS <type> n+1 numbers, CONNECTIVITY <type> m numbers
//   CELL_TYPES n           n type ids
// METADATA blocks (5.1, ended by a blank line) are skipped; POINT_DATA, CELL_DATA or FIELD
// end the part Sinew reads.
#include <fmt/format.h>
#include <limits>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/text_scanner.hpp"
#include "sinew/io/vtk_cells.hpp"

namespace sinew {
namespace {

// Every count is checked against what the rest of the file can hold before anything is sized by it.
std::int64_t read_count(TextScanner& in, const char* what, std::int64_t tokens_each) {
  return in.next_count(what, tokens_each, 0, std::numeric_limits<int>::max());
}

void expect(TextScanner& in, std::string_view keyword) {
  const std::string_view token = in.next(keyword);
  if (token != keyword) in.fail(fmt::format("expected {}, got '{}'", keyword, token));
}

}  // namespace

VolumeMesh read_vtk_legacy_mesh(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  const std::string source = path.string();
  TextScanner in(text, source);

  const std::string_view header = in.next_line("the header");
  if (header.rfind("# vtk DataFile Version", 0) != 0) {
    in.fail("not a legacy VTK file: the first line must start with '# vtk DataFile Version'");
  }
  in.next_line("the title line");
  const std::string_view format = in.next("ASCII or BINARY");
  if (format == "BINARY") in.fail("binary legacy VTK files are not supported; write ASCII or .vtu");
  if (format != "ASCII") in.fail(fmt::format("expected ASCII or BINARY, got '{}'", format));
  expect(in, "DATASET");
  const std::string_view dataset = in.next("the dataset type");
  if (dataset != "UNSTRUCTURED_GRID") {
    in.fail(fmt::format("DATASET {} is not supported; volume meshes are UNSTRUCTURED_GRID", dataset));
  }

  Eigen::MatrixX3d points;
  bool have_points = false, have_cells = false, have_types = false;
  VtkCells cells;
  std::vector<int> cell_lines, type_lines;  // for error messages

  while (!in.at_end()) {
    const std::string_view keyword = in.next("a section keyword");
    if (keyword == "POINTS") {
      if (have_points) in.fail("a second POINTS section");
      const std::int64_t n = read_count(in, "the number of points", 3);
      in.next("the point data type");
      points.resize(static_cast<Eigen::Index>(n), 3);
      for (Eigen::Index p = 0; p < points.rows(); ++p)
        for (int i = 0; i < 3; ++i) points(p, i) = in.next_double("a point coordinate");
      have_points = true;
    } else if (keyword == "CELLS") {
      if (!have_points) in.fail("CELLS before POINTS");
      if (have_cells) in.fail("a second CELLS section");
      const std::int64_t n = read_count(in, "the number of cells", 1);
      const std::int64_t size = read_count(in, "the cell list size", 1);
      if (in.peek() == "OFFSETS") {
        // Version 5.1: n is the number of offsets (cells + 1), size the connectivity length.
        in.next("OFFSETS");
        in.next("the offsets data type");
        if (n < 1) in.fail("CELLS needs at least one offset");
        in.check_count_fits("the offsets and connectivity", n + size, 1);
        cells.offsets.resize(static_cast<std::size_t>(n));
        cell_lines.resize(static_cast<std::size_t>(n));
        for (std::int64_t c = 0; c < n; ++c) {
          cells.offsets[static_cast<std::size_t>(c)] = in.next_integer("an offset");
          cell_lines[static_cast<std::size_t>(c)] = in.line();
        }
        if (cells.offsets.front() != 0) in.fail("the first offset must be 0");
        expect(in, "CONNECTIVITY");
        in.next("the connectivity data type");
        cells.connectivity.resize(static_cast<std::size_t>(size));
        for (auto& v : cells.connectivity) v = in.next_integer("a cell node");
      } else {
        cells.offsets.assign(1, 0);
        cell_lines.clear();
        cells.connectivity.reserve(static_cast<std::size_t>(size > n ? size - n : 0));
        std::int64_t numbers = 0;
        for (std::int64_t c = 0; c < n; ++c) {
          const std::int64_t k = read_count(in, "a cell's node count", 1);
          cell_lines.push_back(in.line());
          for (std::int64_t a = 0; a < k; ++a) cells.connectivity.push_back(in.next_integer("a cell node"));
          numbers += k + 1;
          cells.offsets.push_back(cells.offsets.back() + k);
        }
        if (numbers != size) {
          in.fail(fmt::format("CELLS declares {} numbers but its {} cells hold {}", size, n, numbers));
        }
      }
      have_cells = true;
    } else if (keyword == "CELL_TYPES") {
      if (have_types) in.fail("a second CELL_TYPES section");
      const std::int64_t n = read_count(in, "the number of cell types", 1);
      cells.types.resize(static_cast<std::size_t>(n));
      type_lines.resize(static_cast<std::size_t>(n));
      for (std::int64_t c = 0; c < n; ++c) {
        cells.types[static_cast<std::size_t>(c)] = in.next_integer("a cell type");
        type_lines[static_cast<std::size_t>(c)] = in.line();
      }
      have_types = true;
    } else if (keyword == "METADATA") {
      in.skip_past_blank_line();
    } else if (keyword == "POINT_DATA" || keyword == "CELL_DATA" || keyword == "FIELD") {
      break;
    } else {
      in.fail(fmt::format("unexpected keyword '{}' in an UNSTRUCTURED_GRID", keyword));
    }
  }
  if (!have_points) throw Error("no POINTS section", source);
  if (!have_cells) throw Error("no CELLS section", source);
  if (!have_types) throw Error("no CELL_TYPES section", source);
  if (cells.types.size() + 1 != cells.offsets.size()) {
    throw Error(fmt::format("CELLS has {} cells but CELL_TYPES has {}", cells.offsets.size() - 1,
                            cells.types.size()),
                source);
  }
  return vtk_cells_to_mesh(std::move(points), cells, [&](std::size_t c, VtkCellPart part) {
    const auto& lines = part == VtkCellPart::Type ? type_lines : cell_lines;
    return c < lines.size() ? fmt::format("{}:{}", source, lines[c]) : source;
  });
}

}  // namespace sinew
