#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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

}  // namespace
}  // namespace lwc
