#include "sinew/io/text_scanner.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <system_error>

#include "sinew/core/error.hpp"

namespace sinew {

std::string read_text_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw Error("file does not exist", path.string());
  if (std::filesystem::is_directory(status)) throw Error("is a directory, not a file", path.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open the file for reading", path.string());
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error("reading the file failed", path.string());
  return std::move(text).str();
}

namespace {
// from_chars takes no leading '+', which some writers emit.
const char* skip_plus(std::string_view token) {
  return token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+' ? token.data() + 1
                                                                                 : token.data();
}
}  // namespace

TextScanner::TextScanner(std::string_view text, std::string source, char comment)
    : text_(text), source_(std::move(source)), comment_(comment) {}

std::string TextScanner::where() const { return fmt::format("{}:{}", source_, token_line_); }

void TextScanner::fail(const std::string& message) const { throw Error(message, where()); }

void TextScanner::skip_space() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
    } else if (comment_ != '\0' && c == comment_) {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      return;
    }
  }
}

bool TextScanner::at_end() {
  skip_space();
  return pos_ >= text_.size();
}

std::string_view TextScanner::peek() {
  skip_space();
  std::size_t end = pos_;
  while (end < text_.size() && !std::isspace(static_cast<unsigned char>(text_[end])) &&
         !(comment_ != '\0' && text_[end] == comment_))
    ++end;
  return text_.substr(pos_, end - pos_);
}

std::string_view TextScanner::next(std::string_view what) {
  const std::string_view token = peek();
  if (token.empty()) {
    token_line_ = line_;
    fail(fmt::format("unexpected end of file while reading {}", what));
  }
  token_line_ = line_;
  pos_ += token.size();
  return token;
}

std::string_view TextScanner::next_line(std::string_view what) {
  if (pos_ >= text_.size()) {
    token_line_ = line_;
    fail(fmt::format("unexpected end of file while reading {}", what));
  }
  token_line_ = line_;
  std::size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  std::string_view line = text_.substr(pos_, end - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end < text_.size() ? end + 1 : end;
  if (end < text_.size()) ++line_;
  return line;
}

void TextScanner::skip_past_blank_line() {
  if (pos_ < text_.size()) next_line("a blank line");  // the rest of the current line
  while (pos_ < text_.size()) {
    const std::string_view line = next_line("a blank line");
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) return;
  }
}

std::int64_t TextScanner::next_integer(std::string_view what) {
  const std::string_view token = next(what);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(skip_plus(token), token.data() + token.size(), value);
  if (ec == std::errc::result_out_of_range) fail(fmt::format("{} '{}' is out of range", what, token));
  if (ec != std::errc() || end != token.data() + token.size()) {
    fail(fmt::format("expected an integer for {}, got '{}'", what, token));
  }
  return value;
}

std::int64_t TextScanner::next_count(std::string_view what, std::int64_t tokens_each, std::int64_t lo,
                                     std::int64_t hi) {
  const std::int64_t n = next_integer(what);
  if (n < lo || n > hi) fail(fmt::format("{} {} is out of range [{}, {}]", what, n, lo, hi));
  check_count_fits(what, n, tokens_each);
  return n;
}

void TextScanner::check_count_fits(std::string_view what, std::int64_t count, std::int64_t tokens_each) const {
  const std::int64_t left = static_cast<std::int64_t>(text_.size() - std::min(pos_, text_.size()));
  const std::int64_t most = (left + 1) / 2;  // a token plus its separator, the last one unterminated
  // count <= most / tokens_each, without forming the product (which could overflow). Only a
  // count that would size a large allocation is refused here; a smaller one is left to the
  // parser, which names the exact place where a truncated file ends.
  constexpr std::int64_t kSmall = 1 << 20;  // numbers (8 MB of doubles)
  if (count > 0 && tokens_each > 0 && count > most / tokens_each && count > kSmall / tokens_each)
    fail(fmt::format("{} {} cannot be right: that many need at least {:.0f} numbers, and the {} bytes left in the "
                     "file hold at most {}",
                     what, count, static_cast<double>(count) * static_cast<double>(tokens_each), left, most));
}

double TextScanner::next_double(std::string_view what) {
  const std::string_view token = next(what);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(skip_plus(token), token.data() + token.size(), value);
  if (ec == std::errc::result_out_of_range) fail(fmt::format("{} '{}' is out of range", what, token));
  if (ec != std::errc() || end != token.data() + token.size()) {
    fail(fmt::format("expected a number for {}, got '{}'", what, token));
  }
  if (!std::isfinite(value)) fail(fmt::format("{} '{}' is not a finite number", what, token));
  return value;
}

}  // namespace sinew
