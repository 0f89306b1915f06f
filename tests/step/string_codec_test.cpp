// Escapes of ISO 10303-21 strings against code points taken from the Unicode and ISO 8859 tables.
#include <gtest/gtest.h>

#include "trivar/core/error.hpp"
#include "trivar/io/step/string_codec.hpp"

using namespace trivar;
using namespace trivar::io::step;

TEST(StepStringCodec, DecodesEveryDirective) {
  EXPECT_EQ(decode_string("plain"), "plain");
  EXPECT_EQ(decode_string("back\\\\slash"), "back\\slash");
  EXPECT_EQ(decode_string("\\S\\D"), "\xC3\x84");                // 'D' + 128 = 0xC4, A with diaeresis
  EXPECT_EQ(decode_string("\\PB\\\\S\\!"), "\xC4\x84");          // ISO 8859-2 0xA1 = U+0104
  EXPECT_EQ(decode_string("\\PE\\\\S\\P"), "\xD0\xB0");          // ISO 8859-5 0xD0 = U+0430 (Cyrillic a)
  EXPECT_EQ(decode_string("\\X\\E9t\\X\\E9"), "\xC3\xA9t\xC3\xA9");
  EXPECT_EQ(decode_string("\\X2\\03B103B2\\X0\\"), "\xCE\xB1\xCE\xB2");
  EXPECT_EQ(decode_string("\\X4\\0001F600\\X0\\"), "\xF0\x9F\x98\x80");
  EXPECT_EQ(decode_string("\\X2\\D83DDE00\\X0\\"), "\xF0\x9F\x98\x80");  // surrogate pair, leniently
  EXPECT_EQ(decode_string("a\\X2\\00E9\\X0\\b\\X\\41"), "a\xC3\xA9" "bA");
  EXPECT_EQ(decode_string("\xC3\xA9"), "\xC3\xA9");  // edition 3: UTF-8 kept
}

TEST(StepStringCodec, RejectsBadEscapes) {
  for (const char* bad : {"\\Q\\", "a\\", "\\X\\4", "\\X\\GG", "\\X2\\00E\\X0\\", "\\X2\\00E9", "\\X2\\\\X0\\",
                          "\\X4\\00110000\\X0\\", "\\X2\\D800\\X0\\", "\\PZ\\", "\\S\\\x01", "\\PC\\\\S\\%"}) {
    EXPECT_THROW(decode_string(bad), Error) << bad;
  }
}

TEST(StepStringCodec, EncodesAndRoundTrips) {
  EXPECT_EQ(encode_string("it's a \\ test"), "it''s a \\\\ test");
  EXPECT_EQ(encode_string("\xC3\xA9t\xC3\xA9"), "\\X2\\00E9\\X0\\t\\X2\\00E9\\X0\\");
  EXPECT_EQ(encode_string("\xCE\xB1\xCE\xB2"), "\\X2\\03B103B2\\X0\\");
  EXPECT_EQ(encode_string("\xF0\x9F\x98\x80!"), "\\X4\\0001F600\\X0\\!");
  EXPECT_EQ(encode_string("a\nb"), "a\\X2\\000A\\X0\\b");
  for (const std::string s : {"", "x", "O'Neil \\ \xE2\x82\xAC 100", "\xF0\x9F\x98\x80\xCE\xB1\xF0\x9F\x98\x81 \t"}) {
    std::string raw = encode_string(s), unquoted;
    for (std::size_t i = 0; i < raw.size(); ++i) {  // the lexer's job: '' is one apostrophe
      unquoted += raw[i];
      if (raw[i] == '\'') ++i;
    }
    EXPECT_EQ(decode_string(unquoted), s);
  }
  for (const char* bad : {"\xC3", "\xFF", "\xC0\x80", "\xED\xA0\x80", "\xF4\x90\x80\x80"}) EXPECT_THROW(encode_string(bad), Error);
}
