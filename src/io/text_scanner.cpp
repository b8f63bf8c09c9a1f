#include "sinew/io/text_scanner.hpp"

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
