// Pointer-based scanning of text mesh formats (OBJ, OFF, ASCII PLY): numbers
// are parsed in place with std::from_chars so that large files read at memory
// speed, and the current line is tracked so errors can say where they are.
#pragma once

#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include "intrinsic/error.h"

namespace intrinsic::io {

// Inline whitespace. '\r' counts as blank so CRLF files need no special path;
// other control bytes do not, so binary garbage is reported rather than skipped.
inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

class TextScanner {
 public:
  TextScanner(const char* begin, const char* end, std::string name, int first_line = 1)
      : p_(begin), end_(end), name_(std::move(name)), line_(first_line) {}

  bool at_end() const { return p_ >= end_; }
  int line() const { return line_; }
  const char* pos() const { return p_; }
  const char* end() const { return end_; }
  const std::string& name() const { return name_; }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }

  void skip_blanks() {
    while (p_ < end_ && is_blank(*p_)) ++p_;
  }
  // True at '\n', at end of data, or at a '#' comment (which runs to the end
  // of the line in every format we read).
  bool at_line_end() {
    skip_blanks();
    return p_ >= end_ || *p_ == '\n' || *p_ == '#';
  }
  // Moves past the rest of the current line, whatever it holds.
  void next_line() {
    const void* nl = p_ < end_ ? std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_)) : nullptr;
    if (nl) {
      p_ = static_cast<const char*>(nl) + 1;
      bump_line();
    } else {
      p_ = end_;
    }
  }
  // Skips blanks, newlines and '#' comments, so that the next token may be on
  // a later line (OFF and ASCII PLY bodies are free-form in practice).
  void skip_space_and_comments() {
    while (p_ < end_) {
      char c = *p_;
      if (is_blank(c)) {
        ++p_;
      } else if (c == '\n') {
        ++p_;
        bump_line();
      } else if (c == '#') {
        next_line();
      } else {
        break;
      }
    }
  }

  // Reads the token up to the next blank or newline (may be empty).
  std::string_view word() {
    skip_blanks();
    const char* b = p_;
    while (p_ < end_ && !is_blank(*p_) && *p_ != '\n') ++p_;
    return {b, static_cast<std::size_t>(p_ - b)};
  }

  // Parses a number on the current line; a number must end at a blank, a
  // newline or the end of data, so "1.5abc" is refused rather than read as 1.5.
  bool parse_double(double& out) {
    skip_blanks();
    const char* b = p_;
    if (b < end_ && *b == '+' && b + 1 < end_ && *(b + 1) != '-') ++b;  // from_chars refuses '+'
    auto r = std::from_chars(b, end_, out, std::chars_format::general);
    if (r.ec == std::errc::result_out_of_range) {
      // Underflow is harmless (read as 0); overflow becomes inf so that the
      // caller's finiteness check reports it.
      bool negative_exponent = false;
      for (const char* q = b; q + 1 < r.ptr; ++q)
        if ((*q == 'e' || *q == 'E') && q[1] == '-') negative_exponent = true;
      out = negative_exponent ? 0.0 : HUGE_VAL;
    } else if (r.ec != std::errc()) {
      return false;
    }
    if (r.ptr < end_ && !is_blank(*r.ptr) && *r.ptr != '\n' && *r.ptr != '#') return false;
    p_ = r.ptr;
    return true;
  }

  // Parses an integer token (optionally signed); stops at any non-digit, the
  // caller decides what may follow (OBJ face corners continue with '/').
  bool parse_int64_prefix(std::int64_t& out) {
    const char* b = p_;
    if (b < end_ && *b == '+' && b + 1 < end_ && *(b + 1) != '-') ++b;
    auto r = std::from_chars(b, end_, out);
    if (r.ec == std::errc::result_out_of_range) {
      out = (*b == '-') ? INT64_MIN : INT64_MAX;  // the caller's range check reports it
    } else if (r.ec != std::errc()) {
      return false;
    }
    p_ = r.ptr;
    return true;
  }
  bool parse_int64(std::int64_t& out) {
    skip_blanks();
    if (!parse_int64_prefix(out)) return false;
    return at_token_end();
  }
  bool at_token_end() const {
    return p_ >= end_ || is_blank(*p_) || *p_ == '\n' || *p_ == '#';
  }
  // Moves to `p`, a later position on the current line (a caller that
  // scanned ahead by itself; no newline may lie between).
  void skip_to(const char* p) { p_ = p; }
  bool consume(char c) {
    if (p_ < end_ && *p_ == c) {
      ++p_;
      return true;
    }
    return false;
  }

  [[noreturn]] void fail(const std::string& what) const { fail_at(line_, what); }
  [[noreturn]] void fail_at(int line, const std::string& what) const {
    throw_input(name_ + ":" + std::to_string(line) + ": " + what);
  }

 private:
  // Saturates: a file of more than 2^31 lines is absurd but must not overflow.
  void bump_line() {
    if (line_ < INT_MAX) ++line_;
  }

  const char* p_;
  const char* end_;
  std::string name_;
  int line_;
};

// Quotes a few bytes of the input for messages, with anything unprintable
// escaped so that garbage files cannot garble the terminal.
inline std::string quote_token(std::string_view s) {
  std::string out = "'";
  std::size_t n = 0;
  for (char c : s) {
    if (++n > 32) {
      out += "...";
      break;
    }
    unsigned char u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out += c;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    }
  }
  return out + "'";
}

}  // namespace intrinsic::io
