#pragma once
// Base64 (RFC 4648, standard alphabet, '=' padding, no line breaks), as used by VTK XML
// inline binary arrays. Written here rather than taken from a package: Debian's libb64-dev
// and libbaseencode-dev are compiled C libraries (libb64 also wraps lines), neither is
// installed, and a 60-line codec does not justify a new system dependency.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace sinew {

// Encodes a byte stream given in pieces as one continuous base64 stream (VTK encodes the
// UInt32 size header and the data of an uncompressed array this way).
class Base64Encoder {
 public:
  explicit Base64Encoder(std::string& out) : out_(out) {}
  void append(const void* data, std::size_t size);
  // Emits the pending 1 or 2 bytes with padding; the encoder may not be used afterwards.
  void finish();

 private:
  std::string& out_;
  unsigned char pending_[3] = {0, 0, 0};
  int num_pending_ = 0;
};

// Decodes base64 text, skipping whitespace. Padding ends a quantum and decoding resumes
// after it, so concatenated streams (some writers encode the header block separately) are
// read as one byte sequence. Throws sinew::Error (reason only, the caller adds the place)
// on a character outside the alphabet or a truncated quantum.
std::vector<unsigned char> base64_decode(std::string_view text);

}  // namespace sinew
