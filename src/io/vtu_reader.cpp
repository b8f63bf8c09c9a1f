// VTK XML UnstructuredGrid (.vtu) with inline data, as Sinew's write_vtu and VTK's own writer
// in "ascii" or "binary" (uncompressed) mode produce: one Piece, Points and the Cells arrays
// connectivity, offsets and types. PointData and CellData are not read. The XML is parsed
// by a small non-validating reader that knows elements, attributes, comments and the five
// predefined entities - all that VTK writes.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <type_traits>
#include <fmt/format.h>
#include <limits>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/base64.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/text_scanner.hpp"
#include "sinew/io/vtk_cells.hpp"

namespace sinew {
namespace {

// Arrays this small are parsed whatever their declared size (the parser then names the exact
// problem); a larger declared size the data cannot hold is refused before anything is sized by it.
constexpr std::size_t kSmallArray = std::size_t(1) << 20;

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<XmlElement> children;
  std::vector<std::pair<std::size_t, std::size_t>> text;  // character data between children
  std::size_t offset = 0;                                 // position of '<'

  const std::string* attribute(std::string_view key) const {
    for (const auto& [k, v] : attributes)
      if (k == key) return &v;
    return nullptr;
  }
  std::vector<const XmlElement*> children_named(std::string_view child) const {
    std::vector<const XmlElement*> found;
    for (const auto& c : children)
      if (c.name == child) found.push_back(&c);
    return found;
  }
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Elements nest by recursion; a VTU file needs 5 levels (VTKFile/UnstructuredGrid/Piece/
// Points/DataArray), so a deeper file is refused before it can exhaust the stack.
constexpr int kMaxXmlDepth = 32;

class XmlParser {
 public:
  XmlParser(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  XmlElement parse_document() {
    skip_misc();
    if (pos_ >= text_.size() || text_[pos_] != '<') fail("not an XML file", pos_);
    XmlElement root = parse_element(1);
    skip_misc();
    if (pos_ < text_.size()) fail("content after the root element", pos_);
    return root;
  }

  std::string where(std::size_t offset) const {
    return fmt::format("{}:{}", source_, 1 + std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(std::min(offset, text_.size())), '\n'));
  }
  [[noreturn]] void fail(const std::string& message, std::size_t offset) const {
    throw Error(message, where(offset));
  }

 private:
  bool starts_with(std::string_view s) const { return text_.substr(pos_, s.size()) == s; }

  void skip_to(std::string_view end, const char* what) {
    const std::size_t at = text_.find(end, pos_);
    if (at == std::string_view::npos) fail(fmt::format("unterminated {}", what), pos_);
    pos_ = at + end.size();
  }

  // Whitespace, comments, processing instructions and a DOCTYPE outside elements.
  void skip_misc() {
    for (;;) {
      while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
      if (starts_with("<!--")) {
        skip_to("-->", "comment");
      } else if (starts_with("<?")) {
        skip_to("?>", "processing instruction");
      } else if (starts_with("<!DOCTYPE")) {
        skip_to(">", "DOCTYPE");
      } else {
        return;
      }
    }
  }

  std::string parse_name() {
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_]) && text_[pos_] != '>' && text_[pos_] != '/' &&
           text_[pos_] != '=')
      ++pos_;
    if (pos_ == begin) fail("expected a name", pos_);
    return std::string(text_.substr(begin, pos_ - begin));
  }

  std::string decode(std::string_view raw, std::size_t offset) const {
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const std::size_t semi = raw.find(';', i);
      if (semi == std::string_view::npos) fail("unterminated character reference", offset);
      const std::string_view entity = raw.substr(i + 1, semi - i - 1);
      if (entity == "amp") out += '&';
      else if (entity == "lt") out += '<';
      else if (entity == "gt") out += '>';
      else if (entity == "quot") out += '"';
      else if (entity == "apos") out += '\'';
      else fail(fmt::format("unsupported character reference '&{};'", entity), offset);
      i = semi;
    }
    return out;
  }

  XmlElement parse_element(int depth) {
    if (depth > kMaxXmlDepth)
      fail(fmt::format("elements are nested more than {} levels deep (a VTU file needs 5)", kMaxXmlDepth), pos_);
    XmlElement element;
    element.offset = pos_;
    ++pos_;  // '<'
    element.name = parse_name();
    for (;;) {
      while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
      if (pos_ >= text_.size()) fail(fmt::format("unexpected end of file in the <{}> tag", element.name), element.offset);
      if (starts_with("/>")) {
        pos_ += 2;
        return element;
      }
      if (text_[pos_] == '>') {
        ++pos_;
        break;
      }
      const std::size_t at = pos_;
      std::string key = parse_name();
      while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
      if (pos_ >= text_.size()) fail(fmt::format("unexpected end of file in the <{}> tag", element.name), at);
      if (text_[pos_] != '=') fail(fmt::format("attribute '{}' has no value", key), at);
      ++pos_;
      while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
      if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) {
        fail(fmt::format("attribute '{}' value is not quoted", key), at);
      }
      const char quote = text_[pos_++];
      const std::size_t end = text_.find(quote, pos_);
      if (end == std::string_view::npos) fail(fmt::format("unexpected end of file in attribute '{}'", key), at);
      element.attributes.emplace_back(std::move(key), decode(text_.substr(pos_, end - pos_), at));
      pos_ = end + 1;
    }
    for (;;) {
      const std::size_t lt = text_.find('<', pos_);
      if (lt == std::string_view::npos) fail(fmt::format("<{}> is not closed", element.name), element.offset);
      if (lt > pos_) element.text.emplace_back(pos_, lt);
      pos_ = lt;
      if (starts_with("</")) {
        pos_ += 2;
        const std::string name = parse_name();
        if (pos_ >= text_.size()) fail(fmt::format("unexpected end of file in </{}", name), lt);
        if (name != element.name) {
          fail(fmt::format("</{}> closes <{}>", name, element.name), lt);
        }
        while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
        if (pos_ >= text_.size() || text_[pos_] != '>') fail(fmt::format("unterminated </{}>", name), lt);
        ++pos_;
        return element;
      }
      if (starts_with("<!--")) {
        skip_to("-->", "comment");
      } else if (starts_with("<![CDATA[")) {
        fail("CDATA sections are not supported", lt);
      } else if (starts_with("<?")) {
        skip_to("?>", "processing instruction");
      } else {
        element.children.push_back(parse_element(depth + 1));
      }
    }
  }

  std::string_view text_;
  std::string source_;
  std::size_t pos_ = 0;
};

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64 };

bool scalar_from_name(const std::string& name, Scalar& s) {
  static const std::pair<const char*, Scalar> kNames[] = {
      {"Int8", Scalar::Int8},       {"UInt8", Scalar::UInt8},     {"Int16", Scalar::Int16},
      {"UInt16", Scalar::UInt16},   {"Int32", Scalar::Int32},     {"UInt32", Scalar::UInt32},
      {"Int64", Scalar::Int64},     {"UInt64", Scalar::UInt64},   {"Float32", Scalar::Float32},
      {"Float64", Scalar::Float64}, {"Char", Scalar::Int8},       {"UChar", Scalar::UInt8}};
  for (const auto& [n, v] : kNames)
    if (name == n) {
      s = v;
      return true;
    }
  return false;
}

std::size_t scalar_size(Scalar s) {
  switch (s) {
    case Scalar::Int8: case Scalar::UInt8: return 1;
    case Scalar::Int16: case Scalar::UInt16: return 2;
    case Scalar::Int32: case Scalar::UInt32: case Scalar::Float32: return 4;
    default: return 8;
  }
}

bool is_float(Scalar s) { return s == Scalar::Float32 || s == Scalar::Float64; }

// Copies `size` bytes and reverses them when the file's byte order is not the machine's.
template <class T>
T load(const unsigned char* p, bool swap) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (swap) std::reverse(bytes, bytes + sizeof(T));
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

template <class Out>
Out load_as(Scalar s, const unsigned char* p, bool swap) {
  switch (s) {
    case Scalar::Int8: return static_cast<Out>(load<std::int8_t>(p, swap));
    case Scalar::UInt8: return static_cast<Out>(load<std::uint8_t>(p, swap));
    case Scalar::Int16: return static_cast<Out>(load<std::int16_t>(p, swap));
    case Scalar::UInt16: return static_cast<Out>(load<std::uint16_t>(p, swap));
    case Scalar::Int32: return static_cast<Out>(load<std::int32_t>(p, swap));
    case Scalar::UInt32: return static_cast<Out>(load<std::uint32_t>(p, swap));
    case Scalar::Int64: return static_cast<Out>(load<std::int64_t>(p, swap));
    case Scalar::UInt64: return static_cast<Out>(load<std::uint64_t>(p, swap));
    case Scalar::Float32: return static_cast<Out>(load<float>(p, swap));
    case Scalar::Float64: return static_cast<Out>(load<double>(p, swap));
  }
  return Out{};
}

struct VtuFile {
  const XmlParser& xml;
  std::string_view text;
  bool swap = false;            // file byte order differs from the machine's
  std::size_t header_size = 4;  // UInt32 or UInt64 block header
  std::string compressor;

  // Values of a DataArray as Out (double or int64), with the count checked.
  // `role` names an array without a Name attribute (VTK leaves the Points array unnamed).
  template <class Out>
  std::vector<Out> read(const XmlElement& array, std::size_t expected, const char* role) const {
    const std::string* name_attr = array.attribute("Name");
    const std::string name = name_attr ? *name_attr : std::string(role);
    const auto fail = [&](const std::string& message) -> void {
      throw Error(fmt::format("DataArray '{}': {}", name, message), xml.where(array.offset));
    };
    const std::string* type_attr = array.attribute("type");
    Scalar type{};
    if (!type_attr) fail("no type attribute");
    if (!scalar_from_name(*type_attr, type)) fail(fmt::format("unknown type '{}'", *type_attr));
    if constexpr (std::is_integral_v<Out>) {
      if (is_float(type)) fail(fmt::format("type {} where integers are expected", *type_attr));
    }
    const std::string* format = array.attribute("format");
    if (!format) fail("no format attribute");

    std::string data;
    for (const auto& [b, e] : array.text) {
      data.append(text.substr(b, e - b));
      data += ' ';
    }
    std::vector<Out> values;
    if (*format == "ascii") {
      // Each value takes at least two characters with its separator: a count the text cannot
      // hold is an error here, before anything is sized by it.
      if (expected > (data.size() + 1) / 2 && expected > kSmallArray)
        fail(fmt::format("needs {} values but its text ({} bytes) cannot hold that many", expected, data.size()));
      values.reserve(expected);
      std::size_t i = 0;
      while (i < data.size()) {
        while (i < data.size() && is_space(data[i])) ++i;
        if (i >= data.size()) break;
        std::size_t end = i;
        while (end < data.size() && !is_space(data[end])) ++end;
        Out v{};
        const auto [ptr, ec] = std::from_chars(data.data() + i, data.data() + end, v);
        if (ec != std::errc() || ptr != data.data() + end) {
          fail(fmt::format("value {} '{}' is not {}", values.size(), data.substr(i, end - i),
                           std::is_integral_v<Out> ? "an integer" : "a number"));
        }
        values.push_back(v);
        i = end;
      }
    } else if (*format == "binary") {
      // base64 holds 3 bytes in 4 characters, and a value is >= 1 byte
      if (expected > data.size() && expected > kSmallArray)
        fail(fmt::format("needs {} values but its data ({} characters) cannot hold that many", expected, data.size()));
      if (!compressor.empty()) {
        fail(fmt::format("compressed data ({}) is not supported; write uncompressed binary or ascii", compressor));
      }
      std::vector<unsigned char> bytes;
      try {
        bytes = base64_decode(data);
      } catch (const Error& e) {
        fail(e.message());
      }
      if (bytes.size() < header_size) fail("binary data is shorter than its size header");
      const std::uint64_t size = header_size == 4 ? load<std::uint32_t>(bytes.data(), swap)
                                                  : load<std::uint64_t>(bytes.data(), swap);
      if (size != bytes.size() - header_size) {
        fail(fmt::format("size header says {} bytes but {} follow", size, bytes.size() - header_size));
      }
      const std::size_t width = scalar_size(type);
      if (size % width != 0) fail(fmt::format("{} bytes is not a whole number of {} values", size, *type_attr));
      values.resize(size / width);
      const unsigned char* p = bytes.data() + header_size;
      for (std::size_t k = 0; k < values.size(); ++k) values[k] = load_as<Out>(type, p + k * width, swap);
    } else if (*format == "appended") {
      fail("appended data is not supported; write inline ascii or binary arrays");
    } else {
      fail(fmt::format("unknown format '{}'", *format));
    }
    if (values.size() != expected) fail(fmt::format("has {} values, expected {}", values.size(), expected));
    if constexpr (!std::is_integral_v<Out>) {
      for (std::size_t k = 0; k < values.size(); ++k)
        if (!std::isfinite(values[k])) fail(fmt::format("value {} is not finite", k));
    }
    return values;
  }
};

std::int64_t count_attribute(const XmlParser& xml, const XmlElement& e, const char* key) {
  const std::string* value = e.attribute(key);
  if (!value) throw Error(fmt::format("<{}> has no {} attribute", e.name, key), xml.where(e.offset));
  std::int64_t n = 0;
  const auto [ptr, ec] = std::from_chars(value->data(), value->data() + value->size(), n);
  if (ec != std::errc() || ptr != value->data() + value->size() || n < 0 ||
      n > std::numeric_limits<int>::max()) {
    throw Error(fmt::format("<{}> {}=\"{}\" is not a valid count", e.name, key, *value), xml.where(e.offset));
  }
  return n;
}

const XmlElement& only_child(const XmlParser& xml, const XmlElement& parent, const char* name) {
  const auto found = parent.children_named(name);
  if (found.size() != 1) {
    throw Error(fmt::format("<{}> needs exactly one <{}>, found {}", parent.name, name, found.size()),
                xml.where(parent.offset));
  }
  return *found.front();
}

}  // namespace

VolumeMesh read_vtu_mesh(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  const std::string source = path.string();
  // Appended raw data is arbitrary bytes after the XML; refuse it before parsing.
  if (text.find("<AppendedData") != std::string::npos) {
    throw Error("appended data (<AppendedData>) is not supported; write inline ascii or binary arrays",
                source);
  }
  XmlParser xml(text, source);
  const XmlElement root = xml.parse_document();
  if (root.name != "VTKFile") throw Error(fmt::format("root element is <{}>, not <VTKFile>", root.name), source);
  const std::string* type = root.attribute("type");
  if (!type || *type != "UnstructuredGrid") {
    throw Error(fmt::format("VTK XML type '{}' is not supported; only UnstructuredGrid", type ? *type : ""),
                source);
  }
  VtuFile file{xml, text, false, 4, {}};
  if (const std::string* order = root.attribute("byte_order")) {
    if (*order != "LittleEndian" && *order != "BigEndian") {
      throw Error(fmt::format("unknown byte_order '{}'", *order), xml.where(root.offset));
    }
    file.swap = (*order == "LittleEndian") != (std::endian::native == std::endian::little);
  }
  if (const std::string* header = root.attribute("header_type")) {
    if (*header == "UInt64") file.header_size = 8;
    else if (*header != "UInt32") throw Error(fmt::format("unknown header_type '{}'", *header), xml.where(root.offset));
  }
  if (const std::string* compressor = root.attribute("compressor")) file.compressor = *compressor;

  const XmlElement& grid = only_child(xml, root, "UnstructuredGrid");
  const auto pieces = grid.children_named("Piece");
  if (pieces.size() != 1) {
    throw Error(fmt::format("{} <Piece> elements; only single-piece files are supported", pieces.size()),
                xml.where(grid.offset));
  }
  const XmlElement& piece = *pieces.front();
  const std::int64_t num_points = count_attribute(xml, piece, "NumberOfPoints");
  const std::int64_t num_cells = count_attribute(xml, piece, "NumberOfCells");

  const XmlElement& points_element = only_child(xml, piece, "Points");
  const XmlElement& points_array = only_child(xml, points_element, "DataArray");
  const std::string* components = points_array.attribute("NumberOfComponents");
  if (!components || *components != "3") {
    throw Error("the Points DataArray must have NumberOfComponents=\"3\"", xml.where(points_array.offset));
  }
  const auto coordinates = file.read<double>(points_array, static_cast<std::size_t>(3 * num_points), "Points");
  Eigen::MatrixX3d points(num_points, 3);
  for (Eigen::Index p = 0; p < num_points; ++p)
    for (int i = 0; i < 3; ++i) points(p, i) = coordinates[static_cast<std::size_t>(3 * p + i)];

  const XmlElement& cells_element = only_child(xml, piece, "Cells");
  const XmlElement* arrays[3] = {nullptr, nullptr, nullptr};
  const char* names[3] = {"connectivity", "offsets", "types"};
  for (const XmlElement* a : cells_element.children_named("DataArray")) {
    const std::string* name = a->attribute("Name");
    for (int k = 0; k < 3; ++k)
      if (name && *name == names[k]) arrays[k] = a;
  }
  for (int k = 0; k < 3; ++k) {
    if (!arrays[k]) throw Error(fmt::format("<Cells> has no '{}' DataArray", names[k]), xml.where(cells_element.offset));
  }
  VtkCells cells;
  const auto end_offsets = file.read<std::int64_t>(*arrays[1], static_cast<std::size_t>(num_cells), "offsets");
  cells.offsets.reserve(end_offsets.size() + 1);
  cells.offsets.push_back(0);
  cells.offsets.insert(cells.offsets.end(), end_offsets.begin(), end_offsets.end());
  const std::int64_t total = end_offsets.empty() ? 0 : end_offsets.back();
  if (total < 0) throw Error("the last offset is negative", xml.where(arrays[1]->offset));
  cells.connectivity = file.read<std::int64_t>(*arrays[0], static_cast<std::size_t>(total), "connectivity");
  cells.types = file.read<std::int64_t>(*arrays[2], static_cast<std::size_t>(num_cells), "types");
  return vtk_cells_to_mesh(std::move(points), cells, [&](std::size_t c, VtkCellPart part) {
    const XmlElement& a = part == VtkCellPart::Type ? *arrays[2] : *arrays[0];
    return fmt::format("{} (DataArray '{}', cell {})", xml.where(a.offset),
                       part == VtkCellPart::Type ? "types" : "connectivity", c);
  });
}

}  // namespace sinew
