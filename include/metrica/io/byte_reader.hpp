// Bounds-checked readers over a file held in memory, used by the format
// readers: every read that would pass the end of the file throws an
// IoError that says where (byte offset or line) and in which keyword.
#pragma once

#include <metrica/error.hpp>

#include <fmt/core.h>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace metrica::io {

// A 4- or 8-byte value with its bytes reversed (a file of the other byte
// order).
template <class T>
T byteswap(T value) {
  static_assert(sizeof(T) == 4 || sizeof(T) == 8);
  if constexpr (sizeof(T) == 4) {
    std::uint32_t u;
    std::memcpy(&u, &value, 4);
    u = __builtin_bswap32(u);
    std::memcpy(&value, &u, 4);
  } else {
    std::uint64_t u;
    std::memcpy(&u, &value, 8);
    u = __builtin_bswap64(u);
    std::memcpy(&value, &u, 8);
  }
  return value;
}

class ByteReader {
 public:
  ByteReader(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  void set_swap(bool swap) { swap_ = swap; }
  void set_context(std::string_view keyword) { context_ = keyword; }
  std::size_t pos() const { return pos_; }
  std::size_t size() const { return bytes_.size(); }
  std::size_t left() const { return bytes_.size() - pos_; }
  bool at_end() const { return pos_ >= bytes_.size(); }
  void seek(std::size_t pos) { pos_ = pos; }

  [[noreturn]] void fail(const std::string& what) const { fail_at(what, pos_); }
  [[noreturn]] void fail_at(const std::string& what, std::size_t offset) const {
    if (context_.empty()) throw IoError(fmt::format("{}: {} (at byte offset {})", file_, what, offset));
    throw IoError(fmt::format("{}: {} (keyword {}, at byte offset {})", file_, what, context_, offset));
  }

  void need(std::uint64_t n) const {
    if (n > left()) fail(fmt::format("file is truncated: {} more bytes needed, {} left", n, left()));
  }

  template <class T>
  T raw() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    if (swap_) value = byteswap(value);
    return value;
  }

  std::int64_t integer(int width) { return width == 4 ? raw<std::int32_t>() : raw<std::int64_t>(); }
  double real(int width) { return width == 4 ? static_cast<double>(raw<float>()) : raw<double>(); }

 private:
  std::string_view bytes_;
  const std::string& file_;
  std::size_t pos_ = 0;
  bool swap_ = false;
  std::string_view context_;
};

// Whitespace-separated tokens with line tracking; '#' starts a comment
// that runs to the end of the line.
class TextReader {
 public:
  TextReader(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  void set_context(std::string_view keyword) { context_ = keyword; }
  std::size_t line() const { return line_; }
  std::size_t left() const { return text_.size() - pos_; }

  [[noreturn]] void fail(const std::string& what) const {
    if (context_.empty()) throw IoError(fmt::format("{}:{}: {}", file_, line_, what));
    throw IoError(fmt::format("{}:{}: {} (keyword {})", file_, line_, what, context_));
  }

  // Next token, or an empty view at the end of the text.
  std::string_view token() {
    skip_blank();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  // Looks at the next token without consuming it.
  std::string_view peek() {
    const std::size_t pos = pos_, line = line_;
    const auto tok = token();
    pos_ = pos;
    line_ = line;
    return tok;
  }

  std::int64_t integer(std::string_view what) {
    const auto tok = token();
    if (tok.empty()) fail(fmt::format("unexpected end of file, expected {}", what));
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), value);
    if (ec != std::errc() || end != tok.data() + tok.size())
      fail(fmt::format("expected an integer for {}, found '{}'", what, tok));
    return value;
  }

  double real(std::string_view what) {
    const auto tok = token();
    if (tok.empty()) fail(fmt::format("unexpected end of file, expected {}", what));
    double value = 0;
    const char* first = tok.data();
    if (*first == '+') ++first;  // from_chars rejects a leading '+'
    const auto [end, ec] = std::from_chars(first, tok.data() + tok.size(), value);
    if (ec != std::errc() || end != tok.data() + tok.size())
      fail(fmt::format("expected a real number for {}, found '{}'", what, tok));
    return value;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  void skip_blank() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (is_space(c)) {
        ++pos_;
      } else if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        break;
      }
    }
  }

  std::string_view text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  std::string_view context_;
};

}  // namespace metrica::io
