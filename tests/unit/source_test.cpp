#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <random>

#include "core/source.h"

namespace lwc {
namespace {

// json_quoted writes what nlohmann::json writes for a UTF-8 string, which parses back to it; a
// byte that is not UTF-8 becomes U+FFFD, one per byte, and the text is still valid JSON.
TEST(JsonQuoted, WritesWhatTheJsonLibraryWrites) {
  for (std::string text : {std::string(""), std::string("plain"), std::string("\"quotes\" and \\ backslash"),
                           std::string("tab\tline\nreturn\r back\b feed\f"), std::string("\x01\x1f\x7f", 3),
                           std::string("caf\xC3\xA9 \xF0\x9F\x98\x80"), std::string("bad \xFF byte"), std::string("cut \xE2\x82"),
                           std::string("overlong \xC0\xAF"), std::string("surrogate \xED\xA0\x80"), std::string("nul \0 inside", 13)}) {
    std::string back = nlohmann::json::parse(json_quoted(text)).get<std::string>();
    if (!find_invalid_utf8(text)) {
      EXPECT_EQ(json_quoted(text), nlohmann::json(text).dump()) << text;
      EXPECT_EQ(back, text);
    } else {
      EXPECT_FALSE(find_invalid_utf8(back));
      EXPECT_NE(back.find("\xEF\xBF\xBD"), std::string::npos) << text;
    }
  }
}

// Lines, columns and the first invalid byte are read a word or a line at a time: they agree with a
// byte-by-byte reading wherever the multi-byte characters, bad bytes and line ends fall.
TEST(Source, PositionsAndInvalidBytesAgreeWithAByteByByteReading) {
  std::mt19937 rng(20261124);
  const std::vector<std::string> pieces = {"a", "bcdefghij", "\n", "\r\n", "\xC3\xA9", "\xF0\x9F\x98\x80", "\xFF", "\xE2\x82", "\t"};
  for (int round = 0; round < 300; ++round) {
    std::string text;
    for (int k = std::uniform_int_distribution<int>(0, 40)(rng); k > 0; --k) text += pieces[rng() % pieces.size()];
    std::optional<uint32_t> bad;
    for (size_t i = 0; i < text.size() && !bad;) {
      size_t len = utf8_sequence(text, i);
      if (len == 0) bad = static_cast<uint32_t>(i);
      i += len;
    }
    ASSERT_EQ(find_invalid_utf8(text), bad) << round;
    if (bad) continue;  // columns count characters: only for valid text
    Source source("t.usf", text);
    int line = 1, column = 1;
    for (uint32_t i = 0; i <= text.size();) {
      Position at = source.position(i);
      ASSERT_EQ(at.line, line) << round << " at " << i;
      ASSERT_EQ(at.column, column) << round << " at " << i;
      if (i == text.size()) break;
      size_t len = utf8_sequence(text, i);
      if (text[i] == '\n') line += 1, column = 1;
      else column += 1;
      i += static_cast<uint32_t>(len);
    }
    EXPECT_EQ(source.line_count(), line) << round;
  }
}

}  // namespace
}  // namespace lwc
