#include "sinew/io/surface_reader.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/STL.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "sinew/core/error.hpp"
#include "sinew/io/text_scanner.hpp"

namespace sinew {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// ---- line-level checks of ASCII files (CGAL's readers say only "failed") ----

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

std::optional<double> finite_number(std::string_view token) {
  std::string s(token);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<long long> integer(std::string_view token) {
  long long v = 0;
  const char* first = token.data();
  if (!token.empty() && token.front() == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), v);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return v;
}

// Lines of a text with 1-based numbers; comments after `comment` are dropped.
class Lines {
 public:
  Lines(std::string_view text, std::string source, char comment) : text_(text), source_(std::move(source)), comment_(comment) {}
  // The next line that has a token (false at the end).
  bool next(std::vector<std::string_view>& tokens) {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view line = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      if (comment_) line = line.substr(0, line.find(comment_));
      tokens = split(line);
      if (!tokens.empty()) return true;
    }
    return false;
  }
  int line() const { return line_; }
  // Byte offset of the next line's start.
  std::size_t offset() const { return std::min(pos_, text_.size()); }
  [[noreturn]] void fail(const std::string& message) const {
    throw Error(message, fmt::format("{}:{}", source_, line_));
  }
  [[noreturn]] void fail_at_end(const std::string& message) const {
    throw Error(fmt::format("file ends early: {}", message), fmt::format("{}:{}", source_, line_));
  }
  double number(std::string_view token, std::string_view what) const {
    const auto v = finite_number(token);
    if (!v) fail(fmt::format("{} must be a finite number, got '{}'", what, token));
    return *v;
  }
  long long index(std::string_view token, long long lo, long long hi, std::string_view what) const {
    const auto v = integer(token);
    if (!v) fail(fmt::format("{} must be an integer, got '{}'", what, token));
    if (*v < lo || *v > hi) fail(fmt::format("{} {} is out of range [{}, {}]", what, *v, lo, hi));
    return *v;
  }

 private:
  std::string_view text_;
  std::string source_;
  char comment_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

void check_obj(std::string_view text, const std::string& source) {
  Lines in(text, source, '#');
  std::vector<std::string_view> t;
  long long vertices = 0;
  while (in.next(t)) {
    if (t[0] == "v") {
      if (t.size() < 4) in.fail(fmt::format("vertex {} needs three coordinates, got {}", vertices + 1, t.size() - 1));
      for (int i = 1; i <= 3; ++i) in.number(t[i], "a vertex coordinate");
      ++vertices;
    } else if (t[0] == "f") {
      if (t.size() < 4) in.fail(fmt::format("a face needs at least three vertices, got {}", t.size() - 1));
      for (std::size_t i = 1; i < t.size(); ++i) {
        const std::string_view idx = t[i].substr(0, t[i].find('/'));  // "v/vt/vn": the position index
        const long long v = in.index(idx, -vertices, vertices, "a face's vertex index");
        if (v == 0) in.fail("a face's vertex index is 0 (OBJ indices start at 1)");
      }
    }
  }
}

// Vertices and polygons as a file lists them. OFF and PLY are read by Sinew alone: CGAL's
// readers trust what a file says (a fuzzed COFF colour row overflowed a buffer inside CGAL, a
// PLY 'y' stored as uchar failed an assertion there), so for these formats the checks below
// are also the parser and no other interpretation of the bytes exists.
struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<std::size_t>> polygons;
};

PolygonSoup read_off(std::string_view text, const std::string& source) {
  Lines in(text, source, '#');
  std::vector<std::string_view> t;
  if (!in.next(t)) in.fail_at_end("no OFF header");
  // Rows may carry normals, colours or texture coordinates after the position (the header's
  // C, N, ST); only the position is read. 4D and n-dimensional OFF are refused.
  static const std::string_view kHeaders[] = {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCOFF", "STNOFF", "STCNOFF"};
  if (std::find(std::begin(kHeaders), std::end(kHeaders), t[0]) == std::end(kHeaders)) {
    std::string shown(t[0].substr(0, 20));
    for (char& c : shown)
      if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    in.fail(fmt::format("unsupported OFF header '{}' (Sinew reads ASCII OFF, COFF, NOFF, CNOFF and their ST variants; "
                        "not binary, 4D or n-dimensional OFF)",
                        shown));
  }
  t.erase(t.begin());  // "OFF nv nf ne" on one line is allowed
  if (!t.empty() && t[0] == "BINARY") in.fail("binary OFF is not supported; write ASCII OFF");
  if (t.empty() && !in.next(t)) in.fail_at_end("missing the vertex, face and edge counts");
  if (t.size() < 2) in.fail("expected the vertex and face counts");
  const long long nv = in.index(t[0], 0, 1LL << 31, "the vertex count");
  const long long nf = in.index(t[1], 0, 1LL << 31, "the face count");
  // A row is at least two bytes ("0\n"): counts the rest of the file cannot hold are refused
  // before anything is sized by them.
  if (nv + nf > static_cast<long long>(text.size() - std::min(text.size(), in.offset())) / 2)
    in.fail(fmt::format("{} vertices and {} faces do not fit in the {} bytes that follow", nv, nf,
                        text.size() - std::min(text.size(), in.offset())));
  PolygonSoup soup;
  soup.points.reserve(static_cast<std::size_t>(nv));
  soup.polygons.reserve(static_cast<std::size_t>(nf));
  for (long long v = 0; v < nv; ++v) {
    if (!in.next(t)) in.fail_at_end(fmt::format("after {} of {} vertices", v, nv));
    if (t.size() < 3) in.fail(fmt::format("vertex {} needs three coordinates", v));
    soup.points.emplace_back(in.number(t[0], "a vertex coordinate"), in.number(t[1], "a vertex coordinate"),
                             in.number(t[2], "a vertex coordinate"));
  }
  for (long long f = 0; f < nf; ++f) {
    if (!in.next(t)) in.fail_at_end(fmt::format("after {} of {} faces", f, nf));
    const long long k = in.index(t[0], 3, 1 << 20, "a face's vertex count");
    if (static_cast<long long>(t.size()) < k + 1) in.fail(fmt::format("face {} lists fewer than {} vertices", f, k));
    auto& polygon = soup.polygons.emplace_back();
    for (long long i = 1; i <= k; ++i)
      polygon.push_back(static_cast<std::size_t>(in.index(t[i], 0, nv - 1, "a face's vertex index")));
  }
  return soup;
}

void check_ascii_stl(std::string_view text, const std::string& source) {
  Lines in(text, source, '\0');
  std::vector<std::string_view> t;
  int corners = 0;
  bool in_facet = false, ended = false;
  while (in.next(t)) {
    if (t[0] == "facet") {
      if (in_facet) in.fail("'facet' before the previous facet's 'endfacet'");
      in_facet = true, corners = 0;
    } else if (t[0] == "vertex") {
      if (!in_facet) in.fail("'vertex' outside a facet");
      if (t.size() < 4) in.fail("a vertex needs three coordinates");
      for (int i = 1; i <= 3; ++i) in.number(t[i], "a vertex coordinate");
      ++corners;
    } else if (t[0] == "endfacet") {
      if (corners != 3) in.fail(fmt::format("a facet needs three vertices, got {}", corners));
      in_facet = false;
    } else if (t[0] == "endsolid") {
      ended = true;
    }
  }
  if (in_facet || !ended) in.fail_at_end(in_facet ? "inside a facet" : "no 'endsolid'");
}

void check_binary_stl(const std::string& bytes, const std::string& source) {
  if (bytes.size() < 84) throw Error(fmt::format("binary STL needs an 84-byte header, file has {} bytes", bytes.size()), source);
  std::uint32_t n = 0;
  std::memcpy(&n, bytes.data() + 80, 4);  // little-endian, as on every platform Sinew builds for
  const std::uint64_t need = 84 + 50ULL * n;
  if (bytes.size() < need)
    throw Error(fmt::format("binary STL is truncated: {} triangles need {} bytes, file has {} (triangle {} is cut)", n,
                            need, bytes.size(), (bytes.size() - 84) / 50),
                source);
  for (std::uint32_t f = 0; f < n; ++f)
    for (int c = 0; c < 9; ++c) {
      float x = 0;
      std::memcpy(&x, bytes.data() + 84 + 50ULL * f + 12 + 4 * c, 4);
      if (!std::isfinite(x)) throw Error(fmt::format("triangle {} has a non-finite coordinate", f), source);
    }
}

bool is_ascii_stl(const std::string& bytes) {
  if (bytes.rfind("solid", 0) != 0) return false;
  // Binary files may also start with "solid"; a consistent binary size settles it.
  if (bytes.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50ULL * n) return false;
  }
  return bytes.find("facet") != std::string::npos || bytes.find("endsolid") != std::string::npos;
}

// PLY, ASCII or binary in either byte order: the 'vertex' element's x, y and z (any numeric
// type) and the 'face' element's index list ('vertex_indices' or 'vertex_index', else its only
// list); other elements and properties are walked over. Every count is checked against the
// bytes that follow before anything is sized by it (a binary file claiming 2^31-1 faces once
// made CGAL read uninitialised memory). Errors name the line (header, ASCII rows) or the byte
// offset (binary rows).
PolygonSoup read_ply(std::string_view text, const std::string& source) {
  struct Type {
    int size = 0;
    bool is_float = false, is_signed = false;
  };
  struct Property {
    std::string name;
    Type type, count_type;  // count_type.size > 0: a list
  };
  struct Element {
    std::string name;
    long long count = 0;
    std::vector<Property> properties;
  };
  Lines in(text, source, '\0');
  const auto type_of = [&](std::string_view name) {
    static const std::pair<const char*, Type> kTypes[] = {
        {"char", {1, false, true}},   {"int8", {1, false, true}},    {"uchar", {1, false, false}},
        {"uint8", {1, false, false}}, {"short", {2, false, true}},   {"int16", {2, false, true}},
        {"ushort", {2, false, false}}, {"uint16", {2, false, false}}, {"int", {4, false, true}},
        {"int32", {4, false, true}},  {"uint", {4, false, false}},   {"uint32", {4, false, false}},
        {"float", {4, true, true}},   {"float32", {4, true, true}},  {"double", {8, true, true}},
        {"float64", {8, true, true}}};
    for (const auto& [n, type] : kTypes)
      if (name == n) return type;
    in.fail(fmt::format("unknown PLY property type '{}'", name.substr(0, 20)));
  };

  // ---- header
  std::vector<std::string_view> t;
  if (!in.next(t) || t[0] != "ply") in.fail("not a PLY file: its first line must be 'ply'");
  enum class Format { none, ascii, little_endian, big_endian } format = Format::none;
  std::vector<Element> elements;
  while (true) {
    if (!in.next(t)) in.fail_at_end("no 'end_header'");
    if (t[0] == "end_header") break;
    if (t[0] == "format") {
      if (t.size() < 2) in.fail("'format' needs ascii, binary_little_endian or binary_big_endian");
      if (t[1] == "ascii") format = Format::ascii;
      else if (t[1] == "binary_little_endian") format = Format::little_endian;
      else if (t[1] == "binary_big_endian") format = Format::big_endian;
      else in.fail(fmt::format("unknown PLY format '{}'", t[1].substr(0, 30)));
    } else if (t[0] == "element") {
      if (t.size() < 3) in.fail("'element' needs a name and a count");
      elements.push_back({std::string(t[1]), in.index(t[2], 0, 1LL << 31, "an element count"), {}});
    } else if (t[0] == "property") {
      if (elements.empty()) in.fail("a property before any element");
      if (t.size() >= 5 && t[1] == "list") {
        elements.back().properties.push_back({std::string(t[4]), type_of(t[3]), type_of(t[2])});
        if (elements.back().properties.back().count_type.is_float) in.fail("a list's count type must be an integer");
      } else if (t.size() >= 3 && t[1] != "list") {
        elements.back().properties.push_back({std::string(t[2]), type_of(t[1]), {}});
      } else {
        in.fail("'property' needs a type and a name ('property list COUNT_TYPE TYPE NAME' for a list)");
      }
    } else if (t[0] != "comment" && t[0] != "obj_info") {
      in.fail(fmt::format("unknown PLY header line '{}'", t[0].substr(0, 30)));
    }
  }
  if (format == Format::none) in.fail("no 'format' line before 'end_header'");

  // Which properties hold the positions and the face indices.
  const auto find = [&](const std::string& name) -> const Element* {
    for (const Element& e : elements)
      if (e.name == name) return &e;
    return nullptr;
  };
  const Element* vertex = find("vertex");
  const Element* face = find("face");
  if (!vertex) in.fail("the header declares no 'vertex' element");
  int xyz[3];
  for (int c = 0; c < 3; ++c) {
    const std::string name(1, "xyz"[c]);
    const auto& ps = vertex->properties;
    const auto it = std::find_if(ps.begin(), ps.end(), [&](const Property& p) { return p.name == name; });
    if (it == ps.end() || it->count_type.size) in.fail(fmt::format("the 'vertex' element has no scalar property '{}'", name));
    xyz[c] = static_cast<int>(it - ps.begin());
  }
  int face_list = -1;
  if (face) {
    const auto& ps = face->properties;
    for (std::size_t p = 0; p < ps.size(); ++p)
      if (ps[p].count_type.size && (ps[p].name == "vertex_indices" || ps[p].name == "vertex_index")) face_list = static_cast<int>(p);
    if (face_list < 0 && std::count_if(ps.begin(), ps.end(), [](const Property& p) { return p.count_type.size > 0; }) == 1)
      face_list = static_cast<int>(std::find_if(ps.begin(), ps.end(), [](const Property& p) { return p.count_type.size > 0; }) - ps.begin());
    if (face_list < 0) in.fail("the 'face' element has no list property 'vertex_indices'");
  }
  for (std::size_t e = 0; face && e < elements.size() && &elements[e] != vertex; ++e)
    if (&elements[e] == face) in.fail("the 'face' element comes before the 'vertex' element");

  PolygonSoup soup;
  const long long nv = vertex->count;
  std::size_t pos = in.offset();  // the first byte after the header's last line
  // Each row is at least one byte (binary) or two (ASCII "0\n"): claims the rest cannot hold
  // are refused before reserving.
  for (const Element& e : elements) {
    std::size_t row_bytes = format == Format::ascii ? 2 : 0;
    if (format != Format::ascii)
      for (const Property& p : e.properties) row_bytes += static_cast<std::size_t>(p.count_type.size ? p.count_type.size : p.type.size);
    const std::size_t left = text.size() - std::min(text.size(), pos);
    if (e.count > 0 && !e.properties.empty() && static_cast<std::size_t>(e.count) > left / row_bytes)
      throw Error(fmt::format("element '{}' claims {} rows, which need at least {} bytes, but {} bytes follow", e.name,
                              e.count, static_cast<double>(e.count) * static_cast<double>(row_bytes), left),
                  fmt::format("{}: byte {}", source, pos));
  }
  soup.points.reserve(static_cast<std::size_t>(nv));
  if (face) soup.polygons.reserve(static_cast<std::size_t>(face->count));

  // A face's index list: 3 to 2^20 entries, each a vertex of this file.
  const auto check_face_size = [&](double k, long long row, const std::string& where) {
    if (!(k >= 3 && k <= (1 << 20))) throw Error(fmt::format("face {} has {} vertices (3 to 2^20 allowed)", row, k), where);
  };
  const auto check_index = [&](double v, long long row, const std::string& where) {
    if (!(v >= 0 && v < double(nv) && v == std::floor(v)))
      throw Error(fmt::format("face {} refers to vertex {}, out of range [0, {})", row, v, nv), where);
    return static_cast<std::size_t>(v);
  };

  if (format == Format::ascii) {
    for (const Element& e : elements) {
      if (e.properties.empty()) continue;  // rows without values: nothing to read
      for (long long r = 0; r < e.count; ++r) {
        if (!in.next(t)) in.fail_at_end(fmt::format("after {} of {} {} rows", r, e.count, e.name));
        const std::string where = fmt::format("{}:{}", source, in.line());
        std::size_t k = 0;  // next token
        Eigen::Vector3d point = Eigen::Vector3d::Zero();
        for (std::size_t p = 0; p < e.properties.size(); ++p) {
          const Property& prop = e.properties[p];
          if (k >= t.size()) in.fail(fmt::format("{} row {} has too few values", e.name, r));
          if (!prop.count_type.size) {
            const double v = in.number(t[k++], fmt::format("a '{}' property", e.name));
            if (&e == vertex)
              for (int c = 0; c < 3; ++c)
                if (xyz[c] == static_cast<int>(p)) point(c) = v;
            continue;
          }
          const std::string_view length = t[k++];
          const long long items = in.index(length, 0, static_cast<long long>(t.size() - k), "a list's length");
          if (&e == face && static_cast<int>(p) == face_list) {
            check_face_size(static_cast<double>(items), r, where);
            auto& polygon = soup.polygons.emplace_back();
            for (long long i = 0; i < items; ++i)
              polygon.push_back(check_index(in.number(t[k++], "a face's vertex index"), r, where));
          } else {
            for (long long i = 0; i < items; ++i) in.number(t[k++], fmt::format("a '{}' list entry", e.name));
          }
        }
        if (&e == vertex) soup.points.push_back(point);
      }
    }
    return soup;
  }

  const bool swap = (format == Format::big_endian) != (std::endian::native == std::endian::big);
  const auto read = [&](const Type& type, std::size_t offset) -> double {
    unsigned char b[8];
    std::memcpy(b, text.data() + offset, static_cast<std::size_t>(type.size));
    if (swap) std::reverse(b, b + type.size);
    if (type.is_float) {
      if (type.size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    std::uint64_t u = 0;
    std::memcpy(&u, b, static_cast<std::size_t>(type.size));  // little-endian machine order after the swap
    if (type.is_signed && type.size < 8 && (u >> (8 * type.size - 1)) != 0) u |= ~std::uint64_t{0} << (8 * type.size);
    return type.is_signed ? static_cast<double>(static_cast<std::int64_t>(u)) : static_cast<double>(u);
  };
  const auto at = [&](std::size_t offset) { return fmt::format("{}: byte {}", source, offset); };
  for (const Element& e : elements) {
    if (e.count > 0 && e.properties.empty())
      throw Error(fmt::format("element '{}' has {} rows but no properties", e.name, e.count), at(pos));
    for (long long r = 0; r < e.count; ++r) {
      Eigen::Vector3d point = Eigen::Vector3d::Zero();
      for (std::size_t p = 0; p < e.properties.size(); ++p) {
        const Property& prop = e.properties[p];
        long long items = 1;
        const bool is_face_list = &e == face && static_cast<int>(p) == face_list;
        if (prop.count_type.size) {
          if (pos + static_cast<std::size_t>(prop.count_type.size) > text.size())
            throw Error(fmt::format("file ends in {} row {}", e.name, r), at(pos));
          const double k = read(prop.count_type, pos);
          if (is_face_list) check_face_size(k, r, at(pos));
          if (!(k >= 0 && k <= double(text.size())))
            throw Error(fmt::format("{} row {}: list length {} is out of range", e.name, r, k), at(pos));
          pos += static_cast<std::size_t>(prop.count_type.size);
          items = static_cast<long long>(k);
        }
        if (static_cast<std::size_t>(items) > (text.size() - pos) / static_cast<std::size_t>(prop.type.size))
          throw Error(fmt::format("file ends in {} row {}", e.name, r), at(pos));
        std::vector<std::size_t>* polygon = is_face_list ? &soup.polygons.emplace_back() : nullptr;
        for (long long i = 0; i < items; ++i, pos += static_cast<std::size_t>(prop.type.size)) {
          const double v = read(prop.type, pos);
          if (&e == vertex && !std::isfinite(v))
            throw Error(fmt::format("vertex {} has a property that is not a finite number", r), at(pos));
          if (polygon) polygon->push_back(check_index(v, r, at(pos)));
          if (&e == vertex)
            for (int c = 0; c < 3; ++c)
              if (xyz[c] == static_cast<int>(p)) point(c) = v;
        }
      }
      if (&e == vertex) soup.points.push_back(point);
    }
  }
  return soup;
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

TriangleSurface read_triangle_surface(const std::filesystem::path& path, bool require_closed) {
  const std::string source = path.string();
  const std::string ext = lower_extension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".stl" && ext != ".ply")
    throw Error(fmt::format("unknown surface file extension '{}'; supported: .obj, .off, .stl, .ply", ext), source);
  const std::string bytes = read_text_file(path);  // names the file when it is missing or unreadable
  if (bytes.empty()) throw Error("file is empty", source);

  std::vector<Kernel::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  PolygonSoup soup;  // OFF and PLY: read by Sinew alone
  std::istringstream stream(bytes);
  bool ok = false;
  const char* format = "";
  if (ext == ".obj") {
    format = "OBJ", check_obj(bytes, source);
    ok = CGAL::IO::read_OBJ(stream, points, polygons);
  } else if (ext == ".off") {
    format = "OFF", soup = read_off(bytes, source);
    ok = true;
  } else if (ext == ".ply") {
    format = "PLY", soup = read_ply(bytes, source);
    ok = true;
  } else {
    format = "STL";
    const bool ascii = is_ascii_stl(bytes);
    ascii ? check_ascii_stl(bytes, source) : check_binary_stl(bytes, source);
    std::vector<std::array<std::size_t, 3>> triangles;
    ok = CGAL::IO::read_STL(stream, points, triangles, CGAL::parameters::use_binary_mode(!ascii));
    for (const auto& tri : triangles) polygons.push_back({tri[0], tri[1], tri[2]});
  }
  if (!ok) throw Error(fmt::format("CGAL could not read the file as {} (the format's header or structure is malformed)", format), source);
  for (const Eigen::Vector3d& p : soup.points) points.emplace_back(p.x(), p.y(), p.z());
  for (auto& p : soup.polygons) polygons.push_back(std::move(p));

  TriangleSurface s;
  s.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t v = 0; v < points.size(); ++v)
    s.vertices.row(static_cast<Eigen::Index>(v)) << points[v].x(), points[v].y(), points[v].z();
  std::vector<Eigen::Vector3i> triangles;
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& p = polygons[f];
    if (p.size() < 3) throw Error(fmt::format("polygon {} has only {} vertices", f, p.size()), source);
    for (std::size_t k = 1; k + 1 < p.size(); ++k)  // fan: exact for convex polygons
      triangles.emplace_back(static_cast<int>(p[0]), static_cast<int>(p[k]), static_cast<int>(p[k + 1]));
  }
  s.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) s.faces.row(static_cast<Eigen::Index>(f)) = triangles[f].transpose();
  s.validate(source, require_closed);
  return s;
}

}  // namespace sinew
