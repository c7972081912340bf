// `lwcport lsp` on messages a client got wrong or that carry what JSON carries badly: documents
// that are not UTF-8 (raw bytes, lone surrogates) are analysed as `lint` reads the same bytes; ids
// JSON-RPC and LSP do not allow are refused; parameters of the wrong shape are said to be so in
// plain words.
#include <gtest/gtest.h>

#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/lsp_client.h"
#include "support.h"

namespace lwc {
namespace {

using nlohmann::json;
using namespace lsp_client;

// The inside of a JSON string holding `bytes` as a client may write it: quotes, backslashes and
// control characters escaped, every other byte (UTF-8 or not) as it is.
std::string raw_inside(const std::string& bytes) {
  std::string out;
  for (char c : bytes) {
    if (c == '"' || c == '\\') out += std::string("\\") + c;
    else if (static_cast<unsigned char>(c) < 0x20) out += fmt::format("\\u{:04x}", c);
    else out += c;
  }
  return out;
}

// A framed message whose string "@TEXT@" is replaced by `inside` (a JSON string's inside, as
// written).
std::string frame_with(const json& message, const std::string& inside) {
  std::string body = message.dump();
  body.replace(body.find("@TEXT@"), 6, inside);
  return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

std::string open_with(const std::string& uri, const std::string& inside) {
  return frame_with(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "glsl"}, {"version", 1}, {"text", "@TEXT@"}}}}),
                    inside);
}

// An edit inserting `inside` (as written in JSON) at a line and character.
std::string insert_with(const std::string& uri, int version, int line, int character, const std::string& inside) {
  json at = {{"line", line}, {"character", character}};
  return frame_with(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", version}}},
                                                            {"contentChanges", {{{"range", {{"start", at}, {"end", at}}}, {"text", "@TEXT@"}}}}}),
                    inside);
}

// `lint --format json`'s findings for a file holding `bytes`.
json lint_findings(const std::string& dir, const std::string& bytes) {
  test::write(dir + "/lint.vert", bytes);
  json out = json::parse(test::run(test::binary() + " lint " + dir + "/lint.vert --format json --fail-on none").out);
  return out["findings"];
}

// The last diagnostics published are `lint`'s findings for `bytes`: the same rules, messages and
// places (where every character before a finding on its line is one UTF-16 unit and one column).
void expect_lints_findings(const Session& s, const std::string& dir, const std::string& bytes) {
  json lint = lint_findings(dir, bytes);
  std::vector<json> published = diagnostics(s);
  ASSERT_FALSE(published.empty());
  const json& got = published.back()["diagnostics"];
  ASSERT_EQ(got.size(), lint.size()) << got.dump() << "\n" << lint.dump();
  bool input_warning = false;
  for (size_t i = 0; i < lint.size(); ++i) {
    const json &d = got[i], &f = lint[i];
    std::string hint = f.value("hint", "");
    EXPECT_EQ(d["code"], f["rule"]);
    EXPECT_EQ(d["message"], f["message"].get<std::string>() + (hint.empty() ? "" : "\n" + hint));
    EXPECT_EQ(d["range"]["start"]["line"], f["start"]["line"].get<int>() - 1) << d.dump();
    EXPECT_EQ(d["range"]["start"]["character"], f["start"]["column"].get<int>() - 1) << d.dump();
    input_warning |= f["rule"] == "lwc-input" && f["message"].get<std::string>().find("invalid UTF-8") != std::string::npos;
  }
  EXPECT_TRUE(input_warning) << lint.dump();
}

const std::string kHead = "#version 300 es\n";
const std::string kTail = "uniform mat4 modelMatrix;\nin vec3 position;\nvoid main() { gl_Position = modelMatrix * vec4(position, 1.0); }\n";

// Bytes that are not UTF-8, raw in the JSON of didOpen (as a client that reads files as bytes
// sends them): the document is analysed, with lint's `lwc-input` warning, and the finding after
// them on their line is where the client counts it (each such byte one character).
TEST(LanguageServerInput, RawBytesThatAreNotUtf8InDidOpen) {
  std::string dir = test::scratch("lsp-raw-open");
  std::string bytes = kHead + "/* caf\xE9 \xFF\xFE\xC3 */ " + kTail;
  Session s = serve(frame(initialize()) + open_with("file://" + dir + "/a.vert", raw_inside(bytes)) + end_session());
  expect_lints_findings(s, dir, bytes);
}

// Lone surrogates, escaped (valid JSON): U+DC80..U+DCFF are the bytes 0x80..0xFF they escape, so
// the document is the file's bytes; another lone surrogate is three bytes that are not UTF-8 and
// one UTF-16 unit.
TEST(LanguageServerInput, LoneSurrogatesInDidOpen) {
  std::string dir = test::scratch("lsp-surrogate-open");
  std::string uri = "file://" + dir + "/a.vert";
  Session escaped = serve(frame(initialize()) + open_with(uri, raw_inside(kHead) + "/* caf\\udce9 \\udcff\\udcfe\\udcc3 */ " + raw_inside(kTail)) + end_session());
  expect_lints_findings(escaped, dir, kHead + "/* caf\xE9 \xFF\xFE\xC3 */ " + kTail);

  Session other = serve(frame(initialize()) + open_with(uri, raw_inside(kHead) + "/* \\ud800 */ " + raw_inside(kTail)) + end_session());
  json lint = lint_findings(dir, kHead + "/* \xED\xA0\x80 */ " + kTail);
  std::vector<json> published = diagnostics(other);
  ASSERT_EQ(published.size(), 1u);
  const json& got = published[0]["diagnostics"];
  ASSERT_EQ(got.size(), lint.size());
  ASSERT_EQ(got[0]["code"], "lwc-input");
  EXPECT_EQ(got[0]["message"], lint[0]["message"].get<std::string>() + "\n" + lint[0]["hint"].get<std::string>());
  EXPECT_EQ(got[0]["range"]["start"], json({{"line", 1}, {"character", 3}}));
  bool found = false;
  for (const json& d : got)
    if (d["code"] == "lwc-uniform-world-float") {
      found = true;
      EXPECT_EQ(d["range"]["start"], json({{"line", 1}, {"character", 3 + 1 + 4 + 13}}));  // "/* ", the surrogate, " */ ", "uniform mat4 "
    }
  EXPECT_TRUE(found);
}

// Incremental changes that insert such bytes, raw or as lone surrogates, then an edit placed after
// them on their line (by the client's count): the document is the bytes the client has, and is
// analysed as lint reads them.
TEST(LanguageServerInput, NonUtf8BytesInIncrementalChanges) {
  for (std::string inserted : {std::string("/* \xE9\xFF */ "), std::string("/* \\udce9\\udcff */ ")}) {
    std::string dir = test::scratch("lsp-raw-change");
    std::string uri = "file://" + dir + "/a.vert";
    bool raw = inserted[3] != '\\';
    // Then "uniform " (characters 9 to 17 as the client counts, the two bytes one character each) is
    // replaced by "uniform highp ".
    json range = {{"start", {{"line", 1}, {"character", 9 + 8}}}, {"end", {{"line", 1}, {"character", 9 + 8}}}};
    Session s = serve(frame(initialize()) + frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "glsl"}, {"version", 1}, {"text", kHead + kTail}}}})) +
                      insert_with(uri, 2, 1, 0, raw ? raw_inside(inserted) : inserted) +
                      frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 3}}}, {"contentChanges", {{{"range", range}, {"text", "highp "}}}}})) +
                      end_session());
    ASSERT_FALSE(diagnostics(s).empty());
    EXPECT_EQ(diagnostics(s).back()["version"], 3);
    expect_lints_findings(s, dir, kHead + "/* \xE9\xFF */ uniform highp " + kTail.substr(8));
  }
}

json open_document_notification(const std::string& uri) {
  return notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "glsl"}, {"version", 1}, {"text", kHead + kTail}}}});
}

std::string framed(const std::string& body) { return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body; }

// Ids that are objects, arrays, booleans, null, numbers with a fraction, integers past 32 bits
// (2^70 among them, which no integer holds) or strings that are not UTF-8 are refused: -32600
// Invalid Request with id null, and the method is not run (here `shutdown`: the server still
// answers requests after them). Ids LSP allows come back exactly as they were sent.
TEST(LanguageServerInput, InvalidIdsAreRefusedAndValidOnesComeBackAsSent) {
  const std::vector<std::string> invalid = {R"({"a":1})", "[1]", "true", "false", "null", "1.5", "1e3", "1180591620717411303424",
                                            "2147483648", "-2147483649", "18446744073709551615", "\"\\udce9\"", "\"\xE9\""};
  const std::vector<std::string> valid = {"0", "2147483647", "-2147483648", "\"\"", "\"lwcport/7\"", "\"caf\\u00e9\""};
  std::string input = frame(initialize());
  for (const std::string& id : invalid) input += framed(R"({"jsonrpc":"2.0","id":)" + id + R"(,"method":"shutdown"})");
  for (const std::string& id : valid) input += framed(R"({"jsonrpc":"2.0","id":)" + id + R"(,"method":"no/such"})");
  Session s = serve(input + end_session());
  EXPECT_EQ(s.exit_code, 0);
  int refused = 0;
  for (const json& m : s.messages)
    if (m.contains("error") && m["error"]["code"] == -32600) {
      ++refused;
      EXPECT_TRUE(m["id"].is_null()) << m.dump();
      EXPECT_NE(m["error"]["message"].get<std::string>().find("the request's id "), std::string::npos) << m.dump();
    }
  EXPECT_EQ(refused, static_cast<int>(invalid.size()));
  std::vector<json> answered;
  for (const json& m : s.messages)
    if (m.contains("error") && m["error"]["code"] == -32601) answered.push_back(m["id"]);
  std::vector<json> sent;
  for (const std::string& id : valid) sent.push_back(json::parse(id));
  EXPECT_EQ(answered, sent);
  const json* shutdown = reply_to(s, 99);
  ASSERT_NE(shutdown, nullptr);
  EXPECT_FALSE(shutdown->contains("error"));  // no refused shutdown ran
}

// A message with no method and no result (nor error) is no request and no response: Invalid
// Request, with its id when that is one LSP allows.
TEST(LanguageServerInput, AMessageWithoutAMethodOrAResult) {
  Session s = serve(frame(initialize()) + framed(R"({"jsonrpc":"2.0","id":4})") + framed(R"({"jsonrpc":"2.0","id":4.5,"method":7})") +
                    framed(R"({"jsonrpc":"2.0","id":"lwcport/1","result":null})") + end_session());
  const json* four = reply_to(s, 4);
  ASSERT_NE(four, nullptr);
  EXPECT_EQ((*four)["error"]["code"], -32600);
  int null_ids = 0;
  for (const json& m : s.messages) null_ids += m.contains("error") && m["id"].is_null() && m["error"]["code"] == -32600;
  EXPECT_EQ(null_ids, 1);
  EXPECT_EQ(s.messages.size(), 5u);  // the log line and answer of initialize, the two refusals, shutdown's answer
}

// Parameters a method cannot use get an error that says which member is missing or of what type,
// in plain words: never a library's internals ("[json.exception.out_of_range.403] key ..."), not
// to the client, not in the log.
TEST(LanguageServerInput, BadParametersAreSaidInPlainWords) {
  std::string dir = test::scratch("lsp-bad-params");
  std::string uri = "file://" + dir + "/a.vert";
  json document = {{"uri", uri}};
  json position = {{"line", 1}, {"character", 2}};
  json bad_change = {{"range", {{"start", {{"line", 0}, {"character", true}}}, {"end", position}}}, {"text", ""}};
  std::map<int, std::string> expected = {
      {2, "bad parameters: `position` is missing"},
      {3, "bad parameters: `position.line` must be an integer, not a string"},
      {4, "bad parameters: `range.start` is missing"},
      {5, "bad parameters: `arguments.0` must be a string, not an integer"},
      {6, "bad parameters: `previousResultId` must be a string, not an integer"},
      {7, "bad parameters: `textDocument` is missing"},
      {8, "bad parameters: `action` must be a string, not null"},
  };
  std::string input =
      frame(initialize()) + frame(open_document_notification(uri)) +
      frame(request(2, "textDocument/hover", {{"textDocument", document}})) +
      frame(request(3, "textDocument/hover", {{"textDocument", document}, {"position", {{"line", "1"}, {"character", 0}}}})) +
      frame(request(4, "textDocument/codeAction", {{"textDocument", document}, {"range", {{"end", position}}}})) +
      frame(request(5, "workspace/executeCommand", {{"command", "lwcport.fixAll"}, {"arguments", {5}}})) +
      frame(request(6, "textDocument/diagnostic", {{"textDocument", document}, {"previousResultId", 5}})) +
      frame(request(7, "textDocument/hover", json::array({document}))) +
      frame(request(8, "codeAction/resolve", {{"title", "x"}, {"data", {{"uri", uri}, {"version", 1}, {"action", nullptr}}}})) +
      frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"version", 2}}}})) +
      frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 3}}}, {"contentChanges", json::array({bad_change})}})) +
      frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 4}}}, {"contentChanges", json::object({{"text", 7}})}})) +
      end_session();
  Session s = serve(input, "--log " + dir + "/server.log");
  for (const auto& [id, message] : expected) {
    const json* reply = reply_to(s, id);
    ASSERT_NE(reply, nullptr) << id;
    EXPECT_EQ((*reply)["error"]["code"], -32602) << id;
    EXPECT_EQ((*reply)["error"]["message"], message) << id;
  }
  std::string log = test::read(dir + "/server.log");
  for (const char* line : {"textDocument/didOpen: bad parameters: `textDocument.text` is missing",
                           "textDocument/didChange: bad parameters: `contentChanges.0.range.start.character` must be an integer, not true",
                           "textDocument/didChange: bad parameters: `contentChanges` must be an array, not an object"})
    EXPECT_NE(log.find(line), std::string::npos) << line << "\n" << log;
  std::string written;
  for (const json& m : s.messages) written += m.dump() + "\n";
  for (const std::string& text : {written, log})
    for (const char* internal : {"json.exception", "[json", "type must be", "key '", "basic_string", "what()"})
      EXPECT_EQ(text.find(internal), std::string::npos) << internal << "\n" << text;
}

// A document that is not UTF-8 gets no edit that holds its whole text (JSON would carry those
// bytes as U+FFFD): "fix all" is not offered, and the fix-all command says why instead of editing.
TEST(LanguageServerInput, NoEditLosesBytesThatAreNotUtf8) {
  std::string dir = test::scratch("lsp-raw-fix");
  std::string uri = "file://" + dir + "/a.vert";
  std::string bytes = kHead + "/* \xE9 */\n" + kTail;
  json whole = {{"start", {{"line", 0}, {"character", 0}}}, {"end", {{"line", 9}, {"character", 0}}}};
  Session s = serve(frame(initialize()) + open_with(uri, raw_inside(bytes)) +
                    frame(request(2, "textDocument/codeAction", {{"textDocument", {{"uri", uri}}}, {"range", whole}, {"context", {{"diagnostics", json::array()}}}})) +
                    frame(request(3, "workspace/executeCommand", {{"command", "lwcport.fixAll"}, {"arguments", {uri}}})) + end_session());
  const json* actions = reply_to(s, 2);
  ASSERT_NE(actions, nullptr);
  bool quick_fix = false;
  for (const json& a : (*actions)["result"]) {
    EXPECT_NE(a["kind"], "source.fixAll.lwcport") << a.dump();
    quick_fix |= a["kind"] == "quickfix" && a.contains("edit");
  }
  EXPECT_TRUE(quick_fix);  // a rewrite of one line still is
  EXPECT_TRUE(notifications(s, "workspace/applyEdit").empty());
  for (const json& m : s.messages) EXPECT_NE(m.value("method", ""), "workspace/applyEdit");
  bool said = false;
  for (const json& m : notifications(s, "window/logMessage")) said |= m["message"].get<std::string>().find("is not UTF-8") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace lwc
