#include "trivar/io/step/lexer.hpp"

#include <algorithm>
#include <charconv>

#include "trivar/core/error.hpp"
#include "trivar/io/step/string_codec.hpp"

namespace trivar::io::step {

const char* token_name(TokenKind kind) {
  switch (kind) {
    case TokenKind::end: return "end of file";
    case TokenKind::keyword: return "a keyword";
    case TokenKind::instance_name: return "an instance name";
    case TokenKind::integer: return "an integer";
    case TokenKind::real: return "a real";
    case TokenKind::string: return "a string";
    case TokenKind::enumeration: return "an enumeration";
    case TokenKind::binary: return "a binary";
    case TokenKind::open: return "'('";
    case TokenKind::close: return "')'";
    case TokenKind::comma: return "','";
    case TokenKind::semicolon: return "';'";
    case TokenKind::equals: return "'='";
    case TokenKind::dollar: return "'$'";
    case TokenKind::star: return "'*'";
  }
  return "?";
}

namespace {

bool is_digit(int c) { return c >= '0' && c <= '9'; }
bool is_letter(int c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
bool is_word(int c) { return is_letter(c) || is_digit(c) || c == '_'; }
bool is_hex(int c) { return is_digit(c) || (c >= 'A' && c <= 'F') || (c >= 'a' && c <= 'f'); }
char upper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; }

std::string describe_char(int c) {
  if (c >= 0x21 && c < 0x7F) return std::string("'") + static_cast<char>(c) + "'";
  static const char* hex = "0123456789ABCDEF";
  return std::string("byte 0x") + hex[(c >> 4) & 0xF] + hex[c & 0xF];
}

}  // namespace

Lexer::Lexer(std::istream& in, std::string name, std::size_t chunk_size)
    : name_(std::move(name)), in_(&in), buffer_(std::max<std::size_t>(chunk_size, 16)) {
  begin_ = pos_ = end_ = buffer_.data();
}

Lexer::Lexer(std::string_view text, std::string name) : name_(std::move(name)) {
  begin_ = pos_ = text.data();
  end_ = text.data() + text.size();
}

bool Lexer::refill() {
  if (!in_) return false;
  base_ += static_cast<std::uint64_t>(end_ - begin_);
  in_->read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  const auto n = static_cast<std::size_t>(in_->gcount());
  if (in_->bad()) throw Error(name_ + ": read error");
  begin_ = pos_ = buffer_.data();
  end_ = begin_ + n;
  return n > 0;
}

std::uint32_t Lexer::column() const {
  return static_cast<std::uint32_t>(std::min<std::uint64_t>(offset() - line_start_ + 1, UINT32_MAX));
}

std::string Lexer::where(std::uint32_t at_line, std::uint32_t at_column) const {
  std::string m = name_;  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on chains of operator+
  m += ':';
  m += std::to_string(at_line);
  m += ':';
  m += std::to_string(at_column);
  m += ": ";
  if (instance_) {
    m += '#';
    m += std::to_string(instance_);
    m += ": ";
  }
  return m;
}

void Lexer::fail(std::uint32_t at_line, std::uint32_t at_column, const std::string& message) const {
  throw Error(where(at_line, at_column) + message);
}

void Lexer::upper_case(std::string& word, const Token& t, const char* what) {
  bool lower = false;
  for (char& ch : word) {
    lower |= ch >= 'a' && ch <= 'z';
    ch = upper(ch);
  }
  if (lower && warnings_)
    warnings_->note(Departure::lowercase_keyword, [&] {
      return where(t.line, t.column) + what + " '" + word + "' written in lower case (ISO 10303-21 requires upper case)";
    });
}

template <class Accept>
void Lexer::scan(std::string& out, Accept accept) {
  while (true) {
    const char* p = pos_;
    while (p != end_ && accept(static_cast<unsigned char>(*p))) ++p;
    out.append(pos_, p);
    pos_ = p;
    if (p != end_ || !refill()) return;
  }
}

void Lexer::skip_comment(std::uint32_t at_line, std::uint32_t at_column) {
  bool star = false;
  for (int c; (c = peek()) >= 0; ++pos_) {
    if (star && c == '/') {
      ++pos_;
      return;
    }
    star = c == '*';
    if (c == '\n') newline();
  }
  fail(at_line, at_column, "unterminated comment");
}

void Lexer::skip_blanks_and_comments() {
  for (int c; (c = peek()) >= 0;) {
    if (c == '\n') {
      newline();
      ++pos_;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
    } else if (c == '/') {
      const std::uint32_t l = line_, col = column();
      ++pos_;
      if (peek() != '*') fail(l, col, "unexpected '/' (comments are /* ... */)");
      ++pos_;
      skip_comment(l, col);
    } else {
      return;
    }
  }
}

void Lexer::next(Token& t) {
  skip_blanks_and_comments();
  t.line = line_;
  t.column = column();
  const int c = peek();
  switch (c) {
    case -1: t.kind = TokenKind::end; return;
    case '(': t.kind = TokenKind::open; ++pos_; return;
    case ')': t.kind = TokenKind::close; ++pos_; return;
    case ',': t.kind = TokenKind::comma; ++pos_; return;
    case ';': t.kind = TokenKind::semicolon; ++pos_; return;
    case '=': t.kind = TokenKind::equals; ++pos_; return;
    case '$': t.kind = TokenKind::dollar; ++pos_; return;
    case '*': t.kind = TokenKind::star; ++pos_; return;
    case '\'': lex_string(t); return;
    case '"': lex_binary(t); return;
    case '#': {
      ++pos_;
      scratch_.clear();
      scan(scratch_, is_digit);
      if (scratch_.empty()) fail(t.line, t.column, "expected digits after '#' (constant instance names are not supported)");
      const auto r = std::from_chars(scratch_.data(), scratch_.data() + scratch_.size(), t.id);
      if (r.ec != std::errc() || t.id == 0) fail(t.line, t.column, "bad instance name #" + scratch_);
      t.kind = TokenKind::instance_name;
      return;
    }
    default: break;
  }
  if (c == '.') {
    ++pos_;
    if (is_digit(peek())) {  // .5: not P21, accepted leniently
      scratch_.assign(1, '.');
      lex_number(t);
      return;
    }
    {
      t.text.clear();
      scan(t.text, is_word);
      if (t.text.empty() || peek() != '.') fail(t.line, t.column, "malformed enumeration (expected .NAME.)");
      ++pos_;
      upper_case(t.text, t, "enumeration");
      t.kind = TokenKind::enumeration;
      return;
    }
  }
  if (is_digit(c) || c == '+' || c == '-') {
    scratch_.clear();
    lex_number(t);
    return;
  }
  if (is_letter(c) || c == '_' || c == '!') {
    t.text.clear();
    if (c == '!') {
      t.text += '!';
      ++pos_;
    }
    scan(t.text, [](int ch) { return is_word(ch) || ch == '-'; });
    upper_case(t.text, t, "keyword");
    if (t.text.size() == (c == '!' ? 1u : 0u)) fail(t.line, t.column, "empty user-defined keyword");
    if (t.text.find('-') != std::string::npos && t.text != "ISO-10303-21" && t.text != "END-ISO-10303-21")
      fail(t.line, t.column, "bad keyword '" + t.text + "'");
    t.kind = TokenKind::keyword;
    return;
  }
  fail(t.line, t.column, "unexpected " + describe_char(c));
}

void Lexer::lex_number(Token& t) {
  scan(scratch_, [](int ch) { return is_digit(ch) || ch == '.' || ch == 'E' || ch == 'e' || ch == '+' || ch == '-'; });
  const char* first = scratch_.data();
  const char* last = first + scratch_.size();
  if (*first == '+') ++first;
  const bool real = scratch_.find_first_of(".Ee") != std::string::npos;
  std::from_chars_result r{};
  if (real) {
    r = std::from_chars(first, last, t.real);
    t.kind = TokenKind::real;
  } else {
    r = std::from_chars(first, last, t.integer);
    t.kind = TokenKind::integer;
  }
  if (r.ec == std::errc::result_out_of_range) fail(t.line, t.column, "number out of range '" + scratch_ + "'");
  if (r.ec != std::errc() || r.ptr != last || first == last) fail(t.line, t.column, "malformed number '" + scratch_ + "'");
}

void Lexer::lex_string(Token& t) {
  ++pos_;
  scratch_.clear();
  while (true) {
    scan(scratch_, [](int ch) { return ch != '\'' && ch != '\n' && ch != '\r'; });
    const int c = peek();
    if (c < 0) fail(t.line, t.column, "unterminated string");
    ++pos_;
    if (c == '\n') {
      newline();
    } else if (c == '\'') {
      if (peek() != '\'') break;
      scratch_ += '\'';
      ++pos_;
    }
  }
  StrayBytes stray;
  try {
    t.text = decode_string(scratch_, warnings_ && !warnings_->strict() ? &stray : nullptr);
  } catch (const Error& e) {
    fail(t.line, t.column, e.what());
  }
  if (stray.count > 0)
    warnings_->note(Departure::stray_bytes, [&] { return where(t.line, t.column) + stray_byte_message(stray); });
  t.kind = TokenKind::string;
}

void Lexer::lex_binary(Token& t) {
  ++pos_;
  t.text.clear();
  scan(t.text, is_hex);
  if (peek() != '"') fail(t.line, t.column, "malformed binary (expected hex digits and '\"')");
  ++pos_;
  for (char& ch : t.text) ch = upper(ch);
  if (t.text.empty() || t.text[0] > '3' || (t.text[0] != '0' && t.text.size() == 1))
    fail(t.line, t.column, "malformed binary \"" + t.text + "\" (first digit is the unused bit count 0..3)");
  t.kind = TokenKind::binary;
}

void Lexer::skip_past_semicolon(std::uint32_t at_line, std::uint32_t at_column, std::vector<std::uint64_t>& references) {
  while (true) {
    const char* p = pos_;
    while (p != end_) {
      const char c = *p;
      if (c == ';' || c == '\'' || c == '/' || c == '\n' || c == '#') break;
      ++p;
    }
    pos_ = p;
    const int c = peek();
    if (c < 0) fail(at_line, at_column, "unterminated instance (missing ';')");
    ++pos_;
    if (c == ';') return;
    if (c == '#') {
      std::uint64_t id = 0;
      bool digits = false;
      for (int d; is_digit(d = peek()) && id < UINT64_MAX / 10 - 1; ++pos_) {
        id = id * 10 + static_cast<std::uint64_t>(d - '0');
        digits = true;
      }
      if (digits && id > 0) references.push_back(id);  // malformed names are not checked in skipped bodies
    } else if (c == '\n') {
      newline();
    } else if (c == '\'') {
      for (int s; (s = peek()) != '\''; ++pos_) {
        if (s < 0) fail(at_line, at_column, "unterminated string");
        if (s == '\n') newline();
      }
      ++pos_;  // a doubled '' reads as closing then reopening, which is the same thing here
    } else if (peek() == '*') {
      const std::uint32_t l = line_, col = column();
      ++pos_;
      skip_comment(l, col);
    }
  }
}

void Lexer::skip_section(std::uint32_t at_line, std::uint32_t at_column) {
  // Anchor and reference sections hold <uri> tokens and `#n` names; signature sections a base64 text.
  // Only strings, comments and <...> can hide an ENDSEC that is not the end of the section.
  while (true) {
    skip_blanks_and_comments();
    const int c = peek();
    if (c < 0) fail(at_line, at_column, "section without ENDSEC;");
    if (c == '\'') {
      Token ignored;
      lex_string(ignored);
    } else if (c == '<') {
      for (int s; (s = peek()) != '>'; ++pos_) {
        if (s < 0) fail(at_line, at_column, "unterminated <...> in section");
        if (s == '\n') newline();
      }
      ++pos_;
    } else if (is_letter(c)) {
      scratch_.clear();
      scan(scratch_, is_word);
      if (scratch_ == "ENDSEC") {
        skip_blanks_and_comments();
        if (peek() == ';') {
          ++pos_;
          return;
        }
      }
    } else {
      ++pos_;
    }
  }
}

}  // namespace trivar::io::step
