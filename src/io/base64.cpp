#include "sinew/io/base64.hpp"

#include <array>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

constexpr std::array<signed char, 256> decode_table() {
  std::array<signed char, 256> table{};
  for (auto& v : table) v = -1;
  for (int i = 0; i < 64; ++i) table[static_cast<unsigned char>(kAlphabet[i])] = static_cast<signed char>(i);
  return table;
}
constexpr std::array<signed char, 256> kDecode = decode_table();

void encode_quantum(const unsigned char* b, std::size_t n, char* out) {
  const unsigned v = (unsigned{b[0]} << 16) | (n > 1 ? unsigned{b[1]} << 8 : 0u) | (n > 2 ? unsigned{b[2]} : 0u);
  out[0] = kAlphabet[(v >> 18) & 63];
  out[1] = kAlphabet[(v >> 12) & 63];
  out[2] = n > 1 ? kAlphabet[(v >> 6) & 63] : '=';
  out[3] = n > 2 ? kAlphabet[v & 63] : '=';
}

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

}  // namespace

void Base64Encoder::append(const void* data, std::size_t size) {
  auto bytes = static_cast<const unsigned char*>(data);
  while (num_pending_ > 0 && num_pending_ < 3 && size > 0) {
    pending_[num_pending_++] = *bytes++;
    --size;
  }
  if (num_pending_ == 3) {
    char q[4];
    encode_quantum(pending_, 3, q);
    out_.append(q, 4);
    num_pending_ = 0;
  }
  const std::size_t whole = size / 3;
  const std::size_t start = out_.size();
  out_.resize(start + 4 * whole);
  char* out = out_.data() + start;
  for (std::size_t i = 0; i < whole; ++i) encode_quantum(bytes + 3 * i, 3, out + 4 * i);
  for (std::size_t i = 3 * whole; i < size; ++i) pending_[num_pending_++] = bytes[i];
}

void Base64Encoder::finish() {
  if (num_pending_ > 0) {
    char q[4];
    encode_quantum(pending_, static_cast<std::size_t>(num_pending_), q);
    out_.append(q, 4);
  }
  num_pending_ = 0;
}

std::vector<unsigned char> base64_decode(std::string_view text) {
  std::vector<unsigned char> out;
  out.reserve(text.size() / 4 * 3);
  unsigned quantum = 0;
  int sextets = 0, padding = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (is_space(c)) continue;
    if (c == '=') {
      // '=' may only replace the last one or two sextets of a quantum.
      if (sextets + padding < 2) throw Error(fmt::format("misplaced base64 padding at character {}", i));
      ++padding;
      if (sextets + padding > 4) throw Error(fmt::format("misplaced base64 padding at character {}", i));
    } else {
      const int v = kDecode[static_cast<unsigned char>(c)];
      if (v < 0) throw Error(fmt::format("character '{}' at position {} is not base64", c, i));
      if (padding > 0) throw Error(fmt::format("base64 data after padding at character {}", i));
      quantum = (quantum << 6) | static_cast<unsigned>(v);
      ++sextets;
    }
    if (sextets + padding == 4) {
      quantum <<= 6 * padding;
      out.push_back(static_cast<unsigned char>(quantum >> 16));
      if (sextets > 2) out.push_back(static_cast<unsigned char>(quantum >> 8));
      if (sextets > 3) out.push_back(static_cast<unsigned char>(quantum));
      quantum = 0;
      sextets = padding = 0;
    }
  }
  if (sextets + padding != 0) throw Error("base64 data ends inside a 4-character group");
  return out;
}

}  // namespace sinew
