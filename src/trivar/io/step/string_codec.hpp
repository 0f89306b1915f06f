#pragma once
// ISO 10303-21 string encoding <-> UTF-8. Inside a P21 string, printable ASCII stands for itself except
// that '' is an apostrophe and \\ a backslash; \S\c is c + 128 in the current ISO 8859 page (the
// directives \PA\ .. \PI\ select parts 1 .. 9, part 1 at the start of each string); \X\hh is the
// ISO 8859-1 character hh; \X2\hhhh...\X0\ are UCS-2 characters (surrogate pairs are combined,
// leniently) and \X4\hhhhhhhh...\X0\ UCS-4 characters. The page and UCS conversions are glibc's iconv.
// UTF-8 characters written directly (edition 3 files) are kept.
#include <cstddef>
#include <string>
#include <string_view>

namespace trivar::io::step {

// Bytes a string must not hold: control characters and bytes >= 0x80 that are not UTF-8.
struct StrayBytes {
  std::size_t count = 0;
  std::size_t first_at = 0;  // offset in the raw text
  unsigned char first = 0;
};

// "byte 0x07 at character 3 of a string is not allowed (...)" (and how many there were).
std::string stray_byte_message(const StrayBytes& stray);

// `raw` is the text between the apostrophes with '' already turned into ' and line breaks removed (the
// lexer does both). Throws trivar::Error "bad string escape ..." naming the escape and its offset.
// Stray bytes are an error when `stray` is null; otherwise they are counted there and decoded leniently
// (control characters kept, other bytes read as ISO 8859-1).
std::string decode_string(std::string_view raw, StrayBytes* stray = nullptr);

// The text to put between apostrophes: ' doubled, \ doubled, printable ASCII as is, everything else
// (control characters, non-ASCII) as \X2\..\X0\ runs or, beyond the BMP, \X4\..\X0\ runs.
// Throws trivar::Error on invalid UTF-8.
std::string encode_string(std::string_view utf8);

// Appends the UTF-8 encoding of a code point (caller guarantees <= 0x10FFFF and not a surrogate).
void append_utf8(std::string& out, char32_t cp);

}  // namespace trivar::io::step
