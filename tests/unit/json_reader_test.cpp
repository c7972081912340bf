// The language server's JSON reader: JSON as RFC 8259 has it, but for strings that are not UTF-8,
// which keep the bytes a client sent (lsp/json_reader.h).
#include <gtest/gtest.h>

#include "lsp/json_reader.h"

namespace lwc::lsp {
namespace {

using nlohmann::json;

json read(std::string_view text) {
  JsonRead r = read_json(text);
  EXPECT_EQ(r.error, "") << text;
  return r.value;
}

std::string error_of(std::string_view text) {
  JsonRead r = read_json(text);
  EXPECT_TRUE(r.value.is_null()) << text;
  return r.error;
}

TEST(JsonReader, ReadsWhatNlohmannReads) {
  for (std::string_view text : {R"({"a": [1, -2, 3.5, 1e3, true, false, null, "x\"\\\/\b\f\n\r\t\u00e9\ud83c\udf0d"], "b": {}})",
                                "  [ ]  ", "0", "-0", "18446744073709551615", "-9223372036854775808", "1180591620717411303424", "\"\""})
    EXPECT_EQ(read(text), json::parse(text)) << text;
  EXPECT_TRUE(read("42").is_number_integer());
  EXPECT_TRUE(read("1180591620717411303424").is_number_float());  // 2^70: no integer holds it
}

TEST(JsonReader, KeepsBytesThatAreNotUtf8) {
  EXPECT_EQ(read("\"caf\xE9 \xFF\xC3\""), "caf\xE9 \xFF\xC3");
  EXPECT_EQ(read("{\"\xFE\": 1}")["\xFE"], 1);
}

TEST(JsonReader, LoneSurrogates) {
  EXPECT_EQ(read(R"("caf\udce9 \udcff")"), "caf\xE9 \xFF");          // escaped bytes
  EXPECT_EQ(read(R"("\ud800x\udc41")"), "\xED\xA0\x80x\xED\xB1\x81");  // generalised UTF-8
  EXPECT_EQ(read(R"("\ud800\u0041")"), "\xED\xA0\x80" "A");           // a high one before another escape
  EXPECT_EQ(read(R"("\ud83c\udf0d")"), "\xF0\x9F\x8C\x8D");            // a pair is one character
}

TEST(JsonReader, SaysWhatIsWrongInPlainWords) {
  EXPECT_EQ(error_of("{bad}"), "a member name (a string) expected, found 'b' at byte 1");
  EXPECT_EQ(error_of("{\"a\":1} x"), "more text after the value at byte 8");
  EXPECT_EQ(error_of("\"abc"), "a string that does not end at byte 4");
  EXPECT_EQ(error_of("\"a\x01\""), "a control character (the byte 0x01) inside a string at byte 2");
  EXPECT_EQ(error_of("[1,]"), "a value expected, found ']' at byte 3");
  EXPECT_EQ(error_of("\"\\x\""), "an escape JSON does not have (a backslash, then 'x') at byte 2");
  EXPECT_EQ(error_of("\"\\u12\""), "four hexadecimal digits expected after \\u, found '\"' at byte 5");
  EXPECT_EQ(error_of("1e999"), "a number too large to hold at byte 0");
  EXPECT_EQ(error_of(""), "a value expected, found the end of the text at byte 0");
  EXPECT_EQ(error_of(std::string(kMaxJsonDepth + 1, '[')), "values nested deeper than 200 levels at byte 200");
  for (std::string_view text : {"{bad}", "[1,]", "\"abc", "1e999"}) EXPECT_EQ(error_of(text).find("json.exception"), std::string::npos);
  EXPECT_EQ(read(std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']')).size(), 1u);
}

}  // namespace
}  // namespace lwc::lsp
