#pragma once
// Whitespace-separated tokens of an ASCII file with their line numbers, for the mesh readers:
// every parse failure becomes a sinew::Error whose context is "file:line".
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace sinew {

// The whole file as text; a sinew::Error names the file when it is missing, a directory or
// unreadable.
std::string read_text_file(const std::filesystem::path& path);

class TextScanner {
 public:
  // `comment`: a character that starts a comment running to the end of the line ('\0': none).
  TextScanner(std::string_view text, std::string source, char comment = '\0');

  // True when only whitespace and comments remain.
  bool at_end();
  // The next token; `what` names the expected item for the end-of-file message.
  std::string_view next(std::string_view what);
  // The next token without consuming it (empty at the end).
  std::string_view peek();
  // The rest of the current line (for line-oriented headers), without the newline.
  std::string_view next_line(std::string_view what);
  // Skips the rest of the current line, then lines up to and including the next blank one.
  void skip_past_blank_line();

  std::int64_t next_integer(std::string_view what);
  // A count from the file's header, in [lo, hi], and small enough that `tokens_each` tokens
  // per item fit in what is left of the file (a token takes at least two bytes with its
  // separator). Readers check every count with it before allocating, so a 300-byte file that
  // claims 2^31 cells is an error naming the line, not gigabytes of memory.
  std::int64_t next_count(std::string_view what, std::int64_t tokens_each, std::int64_t lo, std::int64_t hi);
  // Fails unless `count` items of `tokens_each` tokens can fit in the rest of the file.
  void check_count_fits(std::string_view what, std::int64_t count, std::int64_t tokens_each) const;
  // Finite decimal number ("1", "-2.5e-3", "+.5"); NaN and infinity are rejected.
  double next_double(std::string_view what);

  // Line of the last token returned (1-based).
  int line() const { return token_line_; }
  // "source:line"
  std::string where() const;
  [[noreturn]] void fail(const std::string& message) const;

 private:
  void skip_space();

  std::string_view text_;
  std::string source_;
  char comment_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int token_line_ = 1;
};

}  // namespace sinew
