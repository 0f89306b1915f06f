#pragma once
// Tokeniser for ISO 10303-21, written by hand (no packaged P21 library reads the Part 42 volume and
// locally refined entities, see docs/step.md). It reads a stream in fixed-size chunks, so memory does not
// grow with the file, and tracks line and column for messages. Comments /* */ are skipped between tokens;
// line breaks inside strings are dropped (they are not data). Keywords and enumerations are upper-cased
// and stray bytes in strings decoded leniently, each noted as a departure (read_warnings.hpp) when a
// warning collector is set; without one both are accepted silently.
#include <cstdint>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "trivar/io/step/read_warnings.hpp"
#include "trivar/io/step/token.hpp"

namespace trivar::io::step {

class Lexer {
public:
  // Reads `in` in chunks of `chunk_size` bytes; `name` prefixes messages.
  Lexer(std::istream& in, std::string name, std::size_t chunk_size = 1 << 20);
  // Reads text that stays alive as long as the lexer.
  Lexer(std::string_view text, std::string name);

  // Fills `t` with the next token (TokenKind::end at the end of input).
  void next(Token& t);

  // Consumes everything up to and including the next ';' outside strings and comments, without
  // tokenising (fast path for instances a filter drops), appending the ids of the references `#n` met to
  // `references`. Fails at `line:column` when the input ends first.
  void skip_past_semicolon(std::uint32_t at_line, std::uint32_t at_column, std::vector<std::uint64_t>& references);
  // Consumes an edition 3 ANCHOR, REFERENCE or SIGNATURE section body up to and including `ENDSEC;`.
  void skip_section(std::uint32_t at_line, std::uint32_t at_column);

  // Where departures from the standard are noted (strict: refused); null: accepted silently.
  void set_warnings(ReadWarnings* warnings) { warnings_ = warnings; }
  // Instance id that messages name ("#67: "), 0 for none.
  void set_instance(std::uint64_t id) { instance_ = id; }
  // Throws trivar::Error "name:line:column: #id: message".
  [[noreturn]] void fail(std::uint32_t at_line, std::uint32_t at_column, const std::string& message) const;
  // "name:line:column: #id: " for messages.
  std::string where(std::uint32_t at_line, std::uint32_t at_column) const;
  std::uint32_t line() const { return line_; }
  std::uint32_t column() const;
  const std::string& name() const { return name_; }

private:
  int peek() {
    if (pos_ == end_ && !refill()) return -1;
    return static_cast<unsigned char>(*pos_);
  }
  bool refill();
  void newline() {
    ++line_;
    line_start_ = offset() + 1;
  }
  std::uint64_t offset() const { return base_ + static_cast<std::uint64_t>(pos_ - begin_); }
  void skip_blanks_and_comments();
  void skip_comment(std::uint32_t at_line, std::uint32_t at_column);  // after "/*"
  // Appends the longest run of characters in the class to out.
  template <class Accept>
  void scan(std::string& out, Accept accept);
  void lex_number(Token& t);  // appends to scratch_, which may hold a leading '.'
  void lex_string(Token& t);
  void lex_binary(Token& t);
  // Upper-cases a keyword or enumeration name, noting a lower-case one.
  void upper_case(std::string& word, const Token& t, const char* what);

  std::string name_;
  std::istream* in_ = nullptr;
  std::vector<char> buffer_;
  const char* begin_ = nullptr;  // start of the current chunk
  const char* pos_ = nullptr;
  const char* end_ = nullptr;
  std::uint64_t base_ = 0;        // file offset of begin_
  std::uint64_t line_start_ = 0;  // file offset of the first character of the current line
  std::uint32_t line_ = 1;
  std::uint64_t instance_ = 0;
  ReadWarnings* warnings_ = nullptr;
  std::string scratch_;
};

}  // namespace trivar::io::step
