#pragma once
// Tokens of the ISO 10303-21 exchange structure, as produced by Lexer.
#include <cstdint>
#include <string>

namespace trivar::io::step {

enum class TokenKind {
  end,            // end of input
  keyword,        // ENTITY_NAME, !USER_DEFINED, and the ISO-10303-21 / END-ISO-10303-21 markers (text, upper case)
  instance_name,  // #123 (id)
  integer,        // (integer)
  real,           // (real)
  string,         // decoded UTF-8 (text)
  enumeration,    // .NAME. without dots, upper case (text)
  binary,         // "0FF" hex digits, upper case (text)
  open,           // (
  close,          // )
  comma,
  semicolon,
  equals,
  dollar,
  star,
};

const char* token_name(TokenKind kind);

struct Token {
  TokenKind kind = TokenKind::end;
  std::uint32_t line = 0, column = 0;  // where the token starts, 1-based
  std::string text;
  std::int64_t integer = 0;
  double real = 0;
  std::uint64_t id = 0;
};

}  // namespace trivar::io::step
