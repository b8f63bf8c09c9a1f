// Base64 codec: RFC 4648 test vectors, piecewise encoding equals whole encoding, tolerant
// decoding of whitespace and concatenated streams, errors on malformed text.
#include <gtest/gtest.h>

#include <random>

#include "io_test_support.hpp"
#include "sinew/io/base64.hpp"

namespace sinew {
namespace {

std::string encode(std::string_view bytes) {
  std::string out;
  Base64Encoder encoder(out);
  encoder.append(bytes.data(), bytes.size());
  encoder.finish();
  return out;
}

std::string decode(std::string_view text) {
  const auto bytes = base64_decode(text);
  return std::string(bytes.begin(), bytes.end());
}

TEST(IoBase64, Rfc4648Vectors) {
  const std::pair<const char*, const char*> vectors[] = {{"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},  {"foob", "Zm9vYg=="},  {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, coded] : vectors) {
    EXPECT_EQ(encode(plain), coded);
    EXPECT_EQ(decode(coded), plain);
  }
}

TEST(IoBase64, PiecewiseEncodingIsOneStreamAndRoundTrips) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255), cut(0, 40);
  for (int trial = 0; trial < 50; ++trial) {
    std::string data(static_cast<std::size_t>(cut(rng) * 3 + trial % 5), '\0');
    for (auto& c : data) c = static_cast<char>(byte(rng));
    std::string pieces;
    Base64Encoder encoder(pieces);
    std::size_t at = 0;
    while (at < data.size()) {
      const std::size_t n = std::min<std::size_t>(data.size() - at, static_cast<std::size_t>(cut(rng) % 7));
      encoder.append(data.data() + at, n);
      at += n;
    }
    encoder.finish();
    EXPECT_EQ(pieces, encode(data));
    EXPECT_EQ(decode(pieces), data);
  }
}

TEST(IoBase64, DecodingSkipsWhitespaceAndReadsConcatenatedStreams) {
  EXPECT_EQ(decode(" Zm9v\n YmFy\t"), "foobar");
  EXPECT_EQ(decode("Zg==Zm8="), "ffo");  // a separately encoded header followed by data
}

TEST(IoBase64, MalformedTextIsAnError) {
  test::expect_contains(test::error_message([] { base64_decode("Zm9*"); }), {"'*'", "not base64"});
  test::expect_contains(test::error_message([] { base64_decode("Zm9"); }), {"ends inside"});
  test::expect_contains(test::error_message([] { base64_decode("Z==="); }), {"padding"});
  test::expect_contains(test::error_message([] { base64_decode("Zg=a"); }), {"after padding"});
}

}  // namespace
}  // namespace sinew
