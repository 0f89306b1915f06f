#include "trivar/io/step/string_codec.hpp"

#include <iconv.h>

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <memory>

#include "trivar/core/error.hpp"

namespace trivar::io::step {

namespace {

// Character set conversion to UTF-8 by glibc's iconv; one descriptor per set and thread, opened on first use.
class Charset {
public:
  explicit Charset(const char* name) : cd_(iconv_open("UTF-8", name)) {
    require(cd_ != reinterpret_cast<iconv_t>(-1), [&] { return std::string("iconv cannot convert from ") + name; });
  }
  ~Charset() { iconv_close(cd_); }
  Charset(const Charset&) = delete;
  Charset& operator=(const Charset&) = delete;

  // Appends the UTF-8 form of `in`; false (out unchanged) when `in` is not a complete sequence of characters
  // of the set (unassigned positions, unpaired surrogates, code points beyond U+10FFFF).
  bool append(std::string_view in, std::string& out) const {
    iconv(cd_, nullptr, nullptr, nullptr, nullptr);  // initial shift state
    const std::size_t old_size = out.size();
    out.resize(old_size + 4 * in.size());  // UTF-8 needs at most 4 bytes per input byte of these sets
    char* src = const_cast<char*>(in.data());  // iconv's signature; it does not write through src
    std::size_t src_left = in.size();
    char* dst = out.data() + old_size;
    std::size_t dst_left = 4 * in.size();
    const std::size_t r = iconv(cd_, &src, &src_left, &dst, &dst_left);
    if (r == static_cast<std::size_t>(-1) || src_left != 0) {
      out.resize(old_size);
      return false;
    }
    out.resize(static_cast<std::size_t>(dst - out.data()));
    return true;
  }

private:
  iconv_t cd_;
};

// ISO 8859 part 1..9 for \PA\ .. \PI\; UTF-16BE for \X2\ (UCS-2, surrogate pairs combined leniently);
// UTF-32BE for \X4\.
constexpr const char* kCharsets[] = {"ISO-8859-1", "ISO-8859-2", "ISO-8859-3", "ISO-8859-4", "ISO-8859-5",
                                     "ISO-8859-6", "ISO-8859-7", "ISO-8859-8", "ISO-8859-9", "UTF-16BE", "UTF-32BE"};
constexpr int kUtf16 = 9, kUtf32 = 10;

const Charset& charset(int index) {
  thread_local std::unique_ptr<Charset> open[std::size(kCharsets)];
  auto& c = open[static_cast<std::size_t>(index)];
  if (!c) c = std::make_unique<Charset>(kCharsets[index]);
  return *c;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

[[noreturn]] void bad_escape(std::string_view raw, std::size_t at, const std::string& why) {
  const std::string_view shown = raw.substr(at, 12);
  throw Error("bad string escape at character " + std::to_string(at + 1) + " ('" + std::string(shown) + "'): " + why);
}

// Reads n hex digits at raw[at..]; -1 when they are not all hex digits or the string ends.
std::int64_t read_hex(std::string_view raw, std::size_t at, int n) {
  if (at + static_cast<std::size_t>(n) > raw.size()) return -1;
  std::int64_t v = 0;
  for (int k = 0; k < n; ++k) {
    const int d = hex_digit(raw[at + static_cast<std::size_t>(k)]);
    if (d < 0) return -1;
    v = v * 16 + d;
  }
  return v;
}

// The well-formed UTF-8 character starting at s[i]: its length (code point in cp), or 0.
int utf8_char(std::string_view s, std::size_t i, char32_t& cp) {
  const auto b = static_cast<unsigned char>(s[i]);
  int len;
  if (b < 0x80) cp = b, len = 1;
  else if ((b & 0xE0) == 0xC0) cp = b & 0x1Fu, len = 2;
  else if ((b & 0xF0) == 0xE0) cp = b & 0x0Fu, len = 3;
  else if ((b & 0xF8) == 0xF0) cp = b & 0x07u, len = 4;
  else return 0;
  if (i + static_cast<std::size_t>(len) > s.size()) return 0;
  for (int k = 1; k < len; ++k) {
    const auto cb = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
    if ((cb & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (cb & 0x3Fu);
  }
  static constexpr char32_t min_of_length[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < min_of_length[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return len;
}

bool is_printable(unsigned char c) { return c >= 0x20 && c < 0x7F; }

std::string hex_byte(unsigned char c) {
  static const char* hex = "0123456789ABCDEF";
  return std::string("0x") + hex[c >> 4] + hex[c & 0xF];
}

}  // namespace

void append_utf8(std::string& out, char32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

std::string stray_byte_message(const StrayBytes& stray) {
  std::string m = "byte " + hex_byte(stray.first) + " at character " + std::to_string(stray.first_at + 1) +
                  " of a string is not allowed (ISO 10303-21 strings hold printable ISO 8859-1 characters and escapes)";
  if (stray.count > 1) m += "; " + std::to_string(stray.count) + " such bytes in this string";
  return m;
}

std::string decode_string(std::string_view raw, StrayBytes* stray) {
  if (std::all_of(raw.begin(), raw.end(), [](char c) { return is_printable(static_cast<unsigned char>(c)) && c != '\\'; }))
    return std::string(raw);
  std::string out;
  out.reserve(raw.size());
  StrayBytes found;
  int page = 0;  // ISO 8859 part - 1
  std::size_t i = 0;
  while (i < raw.size()) {
    const auto c = static_cast<unsigned char>(raw[i]);
    if (c != '\\') {
      char32_t cp;
      const int len = c >= 0x80 ? utf8_char(raw, i, cp) : 1;
      if (len == 0 || (len == 1 && !is_printable(c))) {
        // Control characters are kept; a byte >= 0x80 outside UTF-8 is read as the ISO 8859-1 character
        // old writers meant by it, so the text stays valid UTF-8.
        if (found.count++ == 0) found.first_at = i, found.first = c;
        append_utf8(out, c);
        ++i;
      } else {  // printable ASCII, or a UTF-8 character written directly (edition 3)
        out.append(raw.substr(i, static_cast<std::size_t>(len)));
        i += static_cast<std::size_t>(len);
      }
      continue;
    }
    const std::size_t at = i;
    if (i + 1 >= raw.size()) bad_escape(raw, at, "lone backslash at the end");
    const char d = raw[i + 1];
    if (d == '\\') {
      out += '\\';
      i += 2;
    } else if (d == 'S' && i + 3 < raw.size() && raw[i + 2] == '\\') {
      const auto ch = static_cast<unsigned char>(raw[i + 3]);
      if (!is_printable(ch)) bad_escape(raw, at, "\\S\\ must be followed by a printable ASCII character");
      const char code = static_cast<char>(ch + 128u);
      if (!charset(page).append(std::string_view(&code, 1), out))
        bad_escape(raw, at, "unassigned character in ISO 8859-" + std::to_string(page + 1));
      i += 4;
    } else if (d == 'P' && i + 3 < raw.size() && raw[i + 3] == '\\') {
      if (raw[i + 2] < 'A' || raw[i + 2] > 'I') bad_escape(raw, at, "code page must be A to I");
      page = raw[i + 2] - 'A';
      i += 4;
    } else if (d == 'X' && i + 2 < raw.size() && raw[i + 2] == '\\') {
      const std::int64_t v = read_hex(raw, i + 3, 2);
      if (v < 0) bad_escape(raw, at, "\\X\\ needs two hex digits");
      append_utf8(out, static_cast<char32_t>(v));  // ISO 8859-1 positions are their Unicode code points
      i += 5;
    } else if (d == 'X' && i + 3 < raw.size() && (raw[i + 2] == '2' || raw[i + 2] == '4') && raw[i + 3] == '\\') {
      const int width = raw[i + 2] == '2' ? 4 : 8;
      i += 4;
      std::string bytes;  // big-endian code units
      while (raw.compare(i, 4, "\\X0\\") != 0) {
        for (int k = 0; k < width; k += 2) {
          const std::int64_t b = read_hex(raw, i, 2);
          if (b < 0) bad_escape(raw, at, "expected " + std::to_string(width) + " hex digits or \\X0\\");
          bytes += static_cast<char>(b);
          i += 2;
        }
      }
      i += 4;
      if (bytes.empty()) bad_escape(raw, at, "empty \\X" + std::string(1, raw[at + 2]) + "\\ group");
      if (!charset(width == 4 ? kUtf16 : kUtf32).append(bytes, out))
        bad_escape(raw, at, "not a Unicode character (unpaired surrogate or beyond U+10FFFF)");
    } else {
      bad_escape(raw, at, "unknown escape");
    }
  }
  if (found.count > 0) {
    if (!stray) throw Error(stray_byte_message(found));
    *stray = found;
  }
  return out;
}

std::string encode_string(std::string_view utf8) {
  std::string out;
  out.reserve(utf8.size() + 2);
  static const char* hex = "0123456789ABCDEF";
  int group = 0;  // open \X2\ (2) or \X4\ (4) run, 0 when none
  auto close = [&] {
    if (group) out += "\\X0\\";
    group = 0;
  };
  std::size_t i = 0;
  while (i < utf8.size()) {
    const auto b = static_cast<unsigned char>(utf8[i]);
    if (b >= 0x20 && b < 0x7F) {
      close();
      if (b == '\'') out += "''";
      else if (b == '\\') out += "\\\\";
      else out += static_cast<char>(b);
      ++i;
      continue;
    }
    char32_t cp;
    const int len = utf8_char(utf8, i, cp);
    if (len == 0) throw Error("invalid UTF-8 in string at byte " + std::to_string(i + 1));
    i += static_cast<std::size_t>(len);
    const int need = cp > 0xFFFF ? 4 : 2;
    if (group != need) {
      close();
      out += need == 2 ? "\\X2\\" : "\\X4\\";
      group = need;
    }
    for (int shift = need == 2 ? 12 : 28; shift >= 0; shift -= 4) out += hex[(cp >> shift) & 0xF];
  }
  close();
  return out;
}

}  // namespace trivar::io::step
