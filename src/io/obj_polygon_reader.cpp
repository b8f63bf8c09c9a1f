#include "sinew/io/obj_polygon_reader.hpp"

#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <string_view>
#include <unordered_map>

#include "sinew/core/error.hpp"
#include "sinew/io/text_scanner.hpp"

namespace sinew {
namespace {

// One line's whitespace-separated tokens.
std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// The rest of a line after its keyword, trimmed (names may contain spaces).
std::string rest_of(std::string_view line, std::string_view keyword) {
  std::string_view r = line.substr(line.find(keyword) + keyword.size());
  while (!r.empty() && (r.front() == ' ' || r.front() == '\t')) r.remove_prefix(1);
  while (!r.empty() && (r.back() == ' ' || r.back() == '\t' || r.back() == '\r')) r.remove_suffix(1);
  return std::string(r);
}

class ObjParser {
 public:
  explicit ObjParser(std::string source) : source_(std::move(source)) {}

  PolygonSurface parse(std::string_view text) {
    std::vector<double> v, vt, vn;
    size_t pos = 0;
    while (pos <= text.size()) {
      ++line_;
      size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      std::string_view line = text.substr(pos, end - pos);
      pos = end + 1;
      if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
      const auto t = split(line);
      if (t.empty()) continue;
      const std::string_view key = t[0];
      if (key == "v") {
        if (t.size() < 4) fail("a vertex needs x y z");
        for (int k = 1; k <= 3; ++k) v.push_back(number(t[k], "vertex coordinate"));
      } else if (key == "vt") {
        if (t.size() < 2) fail("a texture coordinate needs u [v]");
        vt.push_back(number(t[1], "texture coordinate"));
        vt.push_back(t.size() > 2 ? number(t[2], "texture coordinate") : 0.0);
      } else if (key == "vn") {
        if (t.size() != 4) fail("a normal needs x y z");
        for (int k = 1; k <= 3; ++k) vn.push_back(number(t[k], "normal component"));
      } else if (key == "f") {
        face(t, v.size() / 3, vt.size() / 2, vn.size() / 3);
      } else if (key == "g") {
        group_ = t.size() > 1 ? name_index(s_.groups, groups_, rest_of(line, "g")) : -1;
      } else if (key == "o") {
        object_ = t.size() > 1 ? name_index(s_.objects, objects_, rest_of(line, "o")) : -1;
      } else if (key == "usemtl") {
        if (t.size() < 2) fail("usemtl needs a material name");
        material_ = name_index(s_.materials, materials_, rest_of(line, "usemtl"));
      } else if (key == "mtllib") {
        if (t.size() < 2) fail("mtllib needs a file name");
        for (size_t k = 1; k < t.size(); ++k) s_.material_libraries.emplace_back(t[k]);
      } else if (key == "s") {
        if (t.size() != 2) fail("s needs a smoothing group number or off");
        smoothing_ = t[1] == "off" ? 0 : static_cast<int>(integer(t[1], "smoothing group"));
        if (smoothing_ < 0) fail("a smoothing group is 0, off or positive");
      }
      // p, l, curves, surfaces, vp, cstype ...: no surface; skipped.
    }
    s_.positions = to_matrix<Eigen::MatrixX3d>(v, 3);
    s_.uvs = to_matrix<Eigen::MatrixX2d>(vt, 2);
    s_.normals = to_matrix<Eigen::MatrixX3d>(vn, 3);
    if (s_.num_faces() == 0) throw Error("no face (f) in the file", source_);
    return std::move(s_);
  }

 private:
  [[noreturn]] void fail(const std::string& message) const { throw Error(message, fmt::format("{}:{}", source_, line_)); }

  double number(std::string_view token, const char* what) const {
    const char* begin = token.data();
    if (token.size() > 1 && token[0] == '+') ++begin;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(begin, token.data() + token.size(), value);
    if (ec != std::errc() || ptr != token.data() + token.size())
      fail(fmt::format("expected a number for the {}, got '{}'", what, token));
    if (!std::isfinite(value)) fail(fmt::format("the {} is not finite ('{}')", what, token));
    return value;
  }

  long long integer(std::string_view token, const char* what) const {
    long long value = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || ptr != token.data() + token.size() || token.empty())
      fail(fmt::format("expected a whole number for the {}, got '{}'", what, token));
    return value;
  }

  // 1-based, or negative: relative to the end of the list read so far.
  int resolve(std::string_view token, size_t count, const char* what) const {
    const long long i = integer(token, what);
    if (i == 0) fail(fmt::format("{} index 0 (OBJ indices start at 1)", what));
    const long long r = i > 0 ? i - 1 : static_cast<long long>(count) + i;
    if (r < 0 || r >= static_cast<long long>(count))
      fail(fmt::format("{} index {} is out of range (there are {} so far)", what, i, count));
    return static_cast<int>(r);
  }

  void face(const std::vector<std::string_view>& t, size_t nv, size_t nt, size_t nn) {
    if (t.size() < 4) fail(fmt::format("a face needs at least 3 corners, got {}", t.size() - 1));
    std::vector<PolygonSurface::Corner> corners;
    for (size_t k = 1; k < t.size(); ++k) {
      const std::string_view c = t[k];
      const size_t s1 = c.find('/');
      PolygonSurface::Corner corner;
      corner.position = resolve(c.substr(0, s1), nv, "vertex");
      if (s1 != std::string_view::npos) {
        const size_t s2 = c.find('/', s1 + 1);
        const std::string_view uv = c.substr(s1 + 1, s2 == std::string_view::npos ? std::string_view::npos : s2 - s1 - 1);
        if (!uv.empty()) corner.uv = resolve(uv, nt, "texture coordinate");
        if (s2 != std::string_view::npos) corner.normal = resolve(c.substr(s2 + 1), nn, "normal");
      }
      corners.push_back(corner);
    }
    s_.add_face(corners, group_, object_, material_, smoothing_);
  }

  static int name_index(std::vector<std::string>& names, std::unordered_map<std::string, int>& index,
                        const std::string& name) {
    const auto [it, added] = index.emplace(name, static_cast<int>(names.size()));
    if (added) names.push_back(name);
    return it->second;
  }

  template <class Matrix>
  static Matrix to_matrix(const std::vector<double>& values, int cols) {
    Matrix m(static_cast<Eigen::Index>(values.size()) / cols, cols);
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (int c = 0; c < cols; ++c) m(r, c) = values[static_cast<size_t>(r * cols + c)];
    return m;
  }

  std::string source_;
  int line_ = 0;
  PolygonSurface s_;
  int group_ = -1, object_ = -1, material_ = -1, smoothing_ = 0;
  std::unordered_map<std::string, int> groups_, objects_, materials_;
};

}  // namespace

PolygonSurface read_obj_polygon_surface(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  return ObjParser(path.string()).parse(text);
}

}  // namespace sinew
