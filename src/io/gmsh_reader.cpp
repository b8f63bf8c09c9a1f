// Gmsh .msh, ASCII versions 2.2 and 4.1 (the two Gmsh writes; 4.1 is its default). Nodes
// carry arbitrary tags, mapped here to 0-based indices; tetrahedra (type 4) and hexahedra
// (type 5) are the volume elements. Physical groups become the mesh's vertex groups: the
// vertices of the group's points (type 15), lines (1), triangles (2), quads (3), tetrahedra and
// hexahedra, named from $PhysicalNames. Version 2 gives an element's physical tag as its first
// tag; version 4 gives each entity's physical tags in $Entities. Other element types (higher
// order) are skipped. Gmsh's node orders for tetrahedra and hexahedra are VTK's. Binary files are
// rejected with a hint; other sections ($Periodic, $NodeData, ...) are skipped up to their $End line.
#include <algorithm>
#include <charconv>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/text_scanner.hpp"

namespace sinew {
namespace {

constexpr int kGmshTet4 = 4, kGmshHex8 = 5;

// Nodes and dimension of the element types whose vertices a physical group can select.
bool element_shape(int type, std::size_t& nodes, int& dimension) {
  switch (type) {
    case 15: nodes = 1; dimension = 0; return true;  // point
    case 1: nodes = 2; dimension = 1; return true;   // line
    case 2: nodes = 3; dimension = 2; return true;   // triangle
    case 3: nodes = 4; dimension = 2; return true;   // quadrangle
    case kGmshTet4: nodes = 4; dimension = 3; return true;
    case kGmshHex8: nodes = 8; dimension = 3; return true;
    default: return false;
  }
}

using GroupKey = std::pair<int, int>;  // (dimension, physical tag)

struct MshBuilder {
  std::vector<Eigen::Vector3d> points;
  std::unordered_map<std::int64_t, int> index_of_tag;
  std::vector<std::vector<int>> cells;
  int kind = 0;  // kGmshTet4 or kGmshHex8 once an element was kept
  std::map<GroupKey, std::vector<int>> entity_physicals;  // version 4: (dimension, entity tag) -> physical tags
  std::map<GroupKey, std::string> physical_names;
  std::map<GroupKey, std::vector<int>> group_vertices;  // with repeats until finish()

  void add_node(TextScanner& in, std::int64_t tag, const Eigen::Vector3d& x) {
    if (!index_of_tag.emplace(tag, static_cast<int>(points.size())).second) in.fail(fmt::format("node tag {} appears twice", tag));
    points.push_back(x);
  }
  // `rest`: the rest of the element's line: its `skip_tags` tags (version 2), then its nodes.
  // `physicals`: the element's entity's physical tags (version 4; version 2 reads the first tag).
  void add_element(TextScanner& in, std::int64_t tag, int type, std::string_view rest, std::size_t skip_tags,
                   const std::vector<int>* physicals) {
    std::size_t n = 0;
    int dimension = 0;
    if (!element_shape(type, n, dimension)) return;
    std::vector<std::int64_t> numbers;
    for (std::size_t i = 0; i < rest.size();) {
      while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t' || rest[i] == '\r')) ++i;
      const std::size_t start = i;
      while (i < rest.size() && rest[i] != ' ' && rest[i] != '\t' && rest[i] != '\r') ++i;
      if (i == start) break;
      std::int64_t v = 0;
      const auto [end, ec] = std::from_chars(rest.data() + start, rest.data() + i, v);
      if (ec != std::errc() || end != rest.data() + i)
        in.fail(fmt::format("element {}: expected an integer, got '{}'", tag, rest.substr(start, i - start)));
      numbers.push_back(v);
    }
    if (numbers.size() != skip_tags + n)
      in.fail(fmt::format("element {} needs {} tags and {} nodes, the line has {} numbers", tag, skip_tags, n, numbers.size()));
    std::vector<int> cell;
    for (std::size_t a = 0; a < n; ++a) {
      const std::int64_t node = numbers[skip_tags + a];
      const auto it = index_of_tag.find(node);
      if (it == index_of_tag.end()) in.fail(fmt::format("element {} refers to node {}, which is not defined", tag, node));
      cell.push_back(it->second);
    }
    // Version 2: physical tag 0 means none.
    if (skip_tags > 0 && numbers[0] != 0) add_to_group(in, {dimension, numbers[0]}, cell);
    if (physicals)
      for (int p : *physicals) add_to_group(in, {dimension, p}, cell);
    if (dimension != 3) return;
    if (kind != 0 && kind != type) in.fail(fmt::format("element {} mixes hexahedra and tetrahedra (Sinew needs one kind)", tag));
    kind = type;
    cells.push_back(std::move(cell));
  }
  void add_to_group(TextScanner& in, std::pair<int, std::int64_t> key, const std::vector<int>& cell) {
    if (key.second < std::numeric_limits<int>::min() || key.second > std::numeric_limits<int>::max())
      in.fail(fmt::format("physical tag {} is out of range", key.second));
    auto& v = group_vertices[{key.first, static_cast<int>(key.second)}];
    v.insert(v.end(), cell.begin(), cell.end());
  }
  VolumeMesh finish(TextScanner& in) {
    if (cells.empty()) in.fail("the file has no tetrahedra (type 4) or hexahedra (type 5)");
    VolumeMesh mesh;
    mesh.kind = kind == kGmshTet4 ? ElementKind::Tet4 : ElementKind::Hex8;
    mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
    for (std::size_t v = 0; v < points.size(); ++v) mesh.vertices.row(static_cast<Eigen::Index>(v)) = points[v].transpose();
    mesh.elements.resize(static_cast<Eigen::Index>(cells.size()), static_cast<Eigen::Index>(cells[0].size()));
    for (std::size_t e = 0; e < cells.size(); ++e)
      for (std::size_t a = 0; a < cells[e].size(); ++a)
        mesh.elements(static_cast<Eigen::Index>(e), static_cast<Eigen::Index>(a)) = cells[e][a];
    // Named groups without elements are kept (empty), so a selector can say so.
    for (const auto& [key, name] : physical_names) group_vertices[key];
    for (auto& [key, vertices] : group_vertices) {
      std::sort(vertices.begin(), vertices.end());
      vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
      const auto name = physical_names.find(key);
      mesh.groups.push_back({name == physical_names.end() ? "" : name->second, key.second, key.first, std::move(vertices)});
    }
    return mesh;
  }
};

Eigen::Vector3d read_point(TextScanner& in) {
  Eigen::Vector3d x;
  for (int i = 0; i < 3; ++i) x(i) = in.next_double("a node coordinate");
  return x;
}

// `tokens_each`: the fewest tokens each counted item takes, so the count is checked against the
// rest of the file before anything is sized by it.
std::int64_t read_count(TextScanner& in, std::string_view what, std::int64_t tokens_each) {
  return in.next_count(what, tokens_each, 0, std::int64_t{1} << 31);
}

void expect(TextScanner& in, std::string_view token) {
  const std::string_view got = in.next(token);
  if (got != token) in.fail(fmt::format("expected '{}', got '{}'", token, got));
}

void read_nodes_v2(TextScanner& in, MshBuilder& b) {
  const std::int64_t n = read_count(in, "the node count", 4);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t tag = in.next_integer("a node tag");
    b.add_node(in, tag, read_point(in));
  }
  expect(in, "$EndNodes");
}

void read_elements_v2(TextScanner& in, MshBuilder& b) {
  const std::int64_t n = read_count(in, "the element count", 3);
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t tag = in.next_integer("an element tag");
    const std::int64_t type = in.next_integer("an element type");
    const std::int64_t tags = read_count(in, "the number of element tags", 1);
    b.add_element(in, tag, static_cast<int>(type), in.next_line("an element's nodes"), static_cast<std::size_t>(tags), nullptr);
  }
  expect(in, "$EndElements");
}

void read_nodes_v4(TextScanner& in, MshBuilder& b) {
  const std::int64_t blocks = read_count(in, "the node block count", 4);
  read_count(in, "the node count", 4);
  in.next_integer("the minimum node tag");
  in.next_integer("the maximum node tag");
  for (std::int64_t k = 0; k < blocks; ++k) {
    in.next_integer("a block's entity dimension");
    in.next_integer("a block's entity tag");
    const bool parametric = in.next_integer("a block's parametric flag") != 0;
    if (parametric) in.fail("parametric node coordinates are not supported");
    const std::int64_t n = read_count(in, "a block's node count", 4);
    std::vector<std::int64_t> tags(static_cast<size_t>(n));
    for (auto& t : tags) t = in.next_integer("a node tag");
    for (const std::int64_t t : tags) b.add_node(in, t, read_point(in));
  }
  expect(in, "$EndNodes");
}

void read_elements_v4(TextScanner& in, MshBuilder& b) {
  const std::int64_t blocks = read_count(in, "the element block count", 4);
  read_count(in, "the element count", 2);
  in.next_integer("the minimum element tag");
  in.next_integer("the maximum element tag");
  for (std::int64_t k = 0; k < blocks; ++k) {
    const std::int64_t dimension = in.next_integer("a block's entity dimension");
    const std::int64_t entity = in.next_integer("a block's entity tag");
    const std::int64_t type = in.next_integer("a block's element type");
    const std::int64_t n = read_count(in, "a block's element count", 2);
    const auto physicals = b.entity_physicals.find({static_cast<int>(dimension), static_cast<int>(entity)});
    const std::vector<int>* groups = physicals == b.entity_physicals.end() ? nullptr : &physicals->second;
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t tag = in.next_integer("an element tag");
      b.add_element(in, tag, static_cast<int>(type), in.next_line("an element's nodes"), 0, groups);
    }
  }
  expect(in, "$EndElements");
}

int read_int(TextScanner& in, std::string_view what) {
  const std::int64_t v = in.next_integer(what);
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    in.fail(fmt::format("{} {} is out of range", what, v));
  return static_cast<int>(v);
}

// $PhysicalNames: count, then "dimension tag \"name\"" per line.
void read_physical_names(TextScanner& in, MshBuilder& b) {
  const std::int64_t n = read_count(in, "the physical name count", 3);
  for (std::int64_t i = 0; i < n; ++i) {
    const int dimension = read_int(in, "a physical group's dimension");
    const int tag = read_int(in, "a physical tag");
    std::string_view rest = in.next_line("a physical group's name");
    while (!rest.empty() && (rest.front() == ' ' || rest.front() == '\t')) rest.remove_prefix(1);
    while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t' || rest.back() == '\r')) rest.remove_suffix(1);
    if (rest.size() < 2 || rest.front() != '"' || rest.back() != '"')
      in.fail(fmt::format("physical group {} needs a quoted name, got '{}'", tag, rest));
    b.physical_names[{dimension, tag}] = std::string(rest.substr(1, rest.size() - 2));
  }
  expect(in, "$EndPhysicalNames");
}

// Version 4 $Entities: points, curves, surfaces and volumes with their physical tags (the rest of
// each entity's record, its bounding box and boundary, is skipped).
void read_entities_v4(TextScanner& in, MshBuilder& b) {
  std::int64_t counts[4];
  for (int d = 0; d < 4; ++d) counts[d] = read_count(in, "an entity count", d == 0 ? 5 : 9);
  for (int d = 0; d < 4; ++d)
    for (std::int64_t i = 0; i < counts[d]; ++i) {
      const int tag = read_int(in, "an entity tag");
      for (int k = 0; k < (d == 0 ? 3 : 6); ++k) in.next_double("an entity's coordinates");
      const std::int64_t np = read_count(in, "an entity's physical tag count", 1);
      std::vector<int> physicals;
      for (std::int64_t p = 0; p < np; ++p) physicals.push_back(read_int(in, "a physical tag"));
      if (d > 0) {
        const std::int64_t nb = read_count(in, "an entity's boundary count", 1);
        for (std::int64_t k = 0; k < nb; ++k) in.next_integer("a boundary entity tag");
      }
      if (!physicals.empty()) b.entity_physicals[{d, tag}] = std::move(physicals);
    }
  expect(in, "$EndEntities");
}

}  // namespace

VolumeMesh read_gmsh_mesh(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  TextScanner in(text, path.string());
  expect(in, "$MeshFormat");
  const std::string version(in.next("the format version"));
  const std::int64_t file_type = in.next_integer("the file type");
  in.next_integer("the data size");
  if (file_type != 0) in.fail("binary .msh is not supported; save the mesh as ASCII (Gmsh option Mesh.Binary = 0)");
  int major = 0;
  if (version == "2.2" || version == "2.1" || version == "2") {
    major = 2;
  } else if (version == "4.1") {
    major = 4;
  } else {
    in.fail(fmt::format("unsupported .msh version {} (supported: 2.2 and 4.1 ASCII)", version));
  }
  expect(in, "$EndMeshFormat");
  MshBuilder b;
  bool nodes = false, elements = false;
  while (!in.at_end()) {
    const std::string section(in.next("a section"));
    if (section == "$Nodes") {
      major == 2 ? read_nodes_v2(in, b) : read_nodes_v4(in, b);
      nodes = true;
    } else if (section == "$Elements") {
      if (!nodes) in.fail("$Elements before $Nodes");
      major == 2 ? read_elements_v2(in, b) : read_elements_v4(in, b);
      elements = true;
    } else if (section == "$PhysicalNames") {
      read_physical_names(in, b);
    } else if (section == "$Entities" && major == 4) {
      if (elements) in.fail("$Entities after $Elements");
      read_entities_v4(in, b);
    } else if (section.size() > 1 && section[0] == '$') {
      const std::string end = "$End" + section.substr(1);
      while (in.next(end) != end) {
      }
    } else {
      in.fail(fmt::format("expected a section such as $Nodes, got '{}'", section));
    }
  }
  if (!nodes || !elements) in.fail(fmt::format("the file has no {} section", nodes ? "$Elements" : "$Nodes"));
  return b.finish(in);
}

}  // namespace sinew
