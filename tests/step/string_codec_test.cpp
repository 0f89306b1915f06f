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

// One character of every ISO 8859 part \PA\ .. \PI\ selects, against the Unicode consortium's mapping
// tables (MAPPINGS/ISO8859/8859-N.TXT): \S\c is byte c + 128 of that part.
TEST(StepStringCodec, DecodesEveryPageAgainstTheUnicodeTables) {
  EXPECT_EQ(decode_string("\\PA\\\\S\\D"), "\xC3\x84");  // 8859-1 0xC4 = U+00C4
  EXPECT_EQ(decode_string("\\PB\\\\S\\!"), "\xC4\x84");  // 8859-2 0xA1 = U+0104
  EXPECT_EQ(decode_string("\\PC\\\\S\\!"), "\xC4\xA6");  // 8859-3 0xA1 = U+0126
  EXPECT_EQ(decode_string("\\PD\\\\S\\\""), "\xC4\xB8");  // 8859-4 0xA2 = U+0138
  EXPECT_EQ(decode_string("\\PE\\\\S\\P"), "\xD0\xB0");  // 8859-5 0xD0 = U+0430
  EXPECT_EQ(decode_string("\\PF\\\\S\\G"), "\xD8\xA7");  // 8859-6 0xC7 = U+0627
  EXPECT_EQ(decode_string("\\PG\\\\S\\a"), "\xCE\xB1");  // 8859-7 0xE1 = U+03B1
  EXPECT_EQ(decode_string("\\PH\\\\S\\`"), "\xD7\x90");  // 8859-8 0xE0 = U+05D0
  EXPECT_EQ(decode_string("\\PI\\\\S\\P"), "\xC4\x9E");  // 8859-9 0xD0 = U+011E
  // The page holds to the end of the string; \X\ stays ISO 8859-1 whatever the page.
  EXPECT_EQ(decode_string("\\PG\\\\S\\a\\S\\b\\X\\E1"), "\xCE\xB1\xCE\xB2\xC3\xA1");
  EXPECT_THROW(decode_string("\\PF\\\\S\\!"), Error);  // 8859-6 0xA1 is unassigned
  EXPECT_THROW(decode_string("\\PH\\\\S\\!"), Error);  // 8859-8 0xA1 is unassigned
}

TEST(StepStringCodec, StrayBytesAreRefusedOrCountedAndReadAsLatin1) {
  EXPECT_THROW(decode_string("a\x07" "b"), Error);
  EXPECT_THROW(decode_string("caf\xE9"), Error);  // a lone 0xE9 is not UTF-8
  StrayBytes stray;
  EXPECT_EQ(decode_string("a\x07" "b", &stray), "a\x07" "b");
  EXPECT_EQ(stray.count, 1u);
  EXPECT_EQ(stray.first_at, 1u);
  EXPECT_EQ(stray.first, 0x07);
  stray = {};
  EXPECT_EQ(decode_string("\xE9t\xE9 \\X\\E9", &stray), "\xC3\xA9t\xC3\xA9 \xC3\xA9");  // 0xE9 = U+00E9
  EXPECT_EQ(stray.count, 2u);
  EXPECT_EQ(stray.first_at, 0u);
  EXPECT_EQ(stray.first, 0xE9);
  stray = {};
  EXPECT_EQ(decode_string("\xCE\xB1", &stray), "\xCE\xB1");  // well-formed UTF-8 (edition 3) is no stray byte
  EXPECT_EQ(stray.count, 0u);
  EXPECT_EQ(stray_byte_message({3, 4, 0x1B}),
            "byte 0x1B at character 5 of a string is not allowed (ISO 10303-21 strings hold printable ISO 8859-1 "
            "characters and escapes); 3 such bytes in this string");
}

TEST(StepStringCodec, RejectsBadEscapes) {
  for (const char* bad : {"\\Q\\", "a\\", "\\X\\4", "\\X\\GG", "\\X2\\00E\\X0\\", "\\X2\\00E9", "\\X2\\\\X0\\",
                          "\\X4\\00110000\\X0\\", "\\X2\\D800\\X0\\", "\\PZ\\", "\\S\\\x01", "\\PC\\\\S\\%",
                          "\\X4\\0000D800\\X0\\", "\\X2\\DC00D83D\\X0\\", "\\X2\\D83D\\X0\\\\X2\\DE00\\X0\\"}) {
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
