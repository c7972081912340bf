// `lwcport lsp` driven by scripted JSON-RPC sessions: the framed messages go in on standard input,
// every reply and notification is read back from standard output, in order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <nlohmann/json.hpp>

#include "support.h"

namespace lwc {
namespace {

using nlohmann::json;

std::string frame(const json& message) {
  std::string body = message.dump();
  return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

struct Session {
  int exit_code = -1;
  std::vector<json> messages;  // what the server wrote, in order
};

// Every message framed in a server's output, in order.
std::vector<json> read_messages(const std::string& out) {
  std::vector<json> messages;
  for (size_t at = 0; at < out.size();) {
    size_t head = out.find("\r\n\r\n", at);
    if (head == std::string::npos) break;
    size_t length = std::stoul(out.substr(out.find(':', at) + 1, head - at));
    messages.push_back(json::parse(out.substr(head + 4, length)));
    at = head + 4 + length;
  }
  return messages;
}

// Runs the server on `input` (already framed) and reads every message it writes.
Session serve(const std::string& input) {
  std::string dir = test::scratch("lsp");
  test::write(dir + "/in", input);
  test::Run r = test::run(test::binary() + " lsp < " + dir + "/in");
  return {r.exit_code, read_messages(r.out)};
}

json request(int id, const std::string& method, const json& params = json::object()) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", params}};
}
json notification(const std::string& method, const json& params = json::object()) {
  return {{"jsonrpc", "2.0"}, {"method", method}, {"params", params}};
}
json initialize(const json& capabilities = json::object()) { return request(1, "initialize", {{"capabilities", capabilities}}); }
std::string end_session() { return frame(request(99, "shutdown")) + frame(notification("exit")); }

const json* reply_to(const Session& s, int id) {
  for (const json& m : s.messages)
    if (m.contains("id") && m["id"] == id) return &m;
  return nullptr;
}
std::vector<json> diagnostics(const Session& s) {
  std::vector<json> out;
  for (const json& m : s.messages)
    if (m.value("method", "") == "textDocument/publishDiagnostics") out.push_back(m["params"]);
  return out;
}

// The server's diagnostics for a corpus file are `lint`'s findings, at the same places; an edit
// above them moves them down; a malformed message gets a parse error and the server answers the
// next request; an unknown request is "method not found"; shutdown, then exit, ends with 0.
TEST(LanguageServer, DiagnosticsAreLintsFindingsAndFollowEdits) {
  std::string path = test::source_dir() + "/corpus/glsl/forward.vert";
  std::string text = test::read(path);
  std::string uri = "file://" + path;
  json lint = json::parse(test::run(test::binary() + " lint " + path + " --format json --fail-on none").out);
  ASSERT_FALSE(lint["findings"].empty());
  json insert = {{"range", {{"start", {{"line", 0}, {"character", 0}}}, {"end", {{"line", 0}, {"character", 0}}}}}, {"text", "// a\n"}};
  Session s = serve(frame(initialize()) + frame(notification("initialized")) +
                    frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "glsl"}, {"version", 1}, {"text", text}}}})) +
                    frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 2}}}, {"contentChanges", {insert}}})) +
                    "Content-Length: 5\r\n\r\n{bad}" + frame(request(7, "textDocument/noSuchThing")) + end_session());
  EXPECT_EQ(s.exit_code, 0);
  const json* init = reply_to(s, 1);
  ASSERT_NE(init, nullptr);
  EXPECT_EQ((*init)["result"]["capabilities"]["positionEncoding"], "utf-16");
  std::vector<json> published = diagnostics(s);
  ASSERT_EQ(published.size(), 2u);
  EXPECT_EQ(published[0]["version"], 1);
  EXPECT_EQ(published[1]["version"], 2);
  ASSERT_EQ(published[0]["diagnostics"].size(), lint["findings"].size());
  for (size_t i = 0; i < lint["findings"].size(); ++i) {
    const json &d = published[0]["diagnostics"][i], &f = lint["findings"][i], &moved = published[1]["diagnostics"][i];
    EXPECT_EQ(d["code"], f["rule"]);
    EXPECT_EQ(d["source"], "lwcport");
    EXPECT_EQ(d["range"]["start"]["line"], f["start"]["line"].get<int>() - 1);  // lint: 1-based lines and columns
    EXPECT_EQ(d["range"]["start"]["character"], f["start"]["column"].get<int>() - 1);
    EXPECT_EQ(moved["range"]["start"]["line"], d["range"]["start"]["line"].get<int>() + 1);
    EXPECT_NE(d["codeDescription"]["href"].get<std::string>().find(f["rule"].get<std::string>()), std::string::npos);
  }
  bool parse_error = false;
  for (const json& m : s.messages) parse_error |= m.contains("error") && m["error"]["code"] == -32700 && m["id"].is_null();
  EXPECT_TRUE(parse_error);
  const json* unknown = reply_to(s, 7);
  ASSERT_NE(unknown, nullptr);
  EXPECT_EQ((*unknown)["error"]["code"], -32601);
  const json* shutdown = reply_to(s, 99);
  ASSERT_NE(shutdown, nullptr);
  EXPECT_TRUE((*shutdown)["result"].is_null());
}

// Columns count UTF-16 code units unless the client offers UTF-8: a character outside the BMP
// (two UTF-16 units, four bytes) before a finding moves it by 2 or by 4. An edit given in those
// units lands where the client means it.
TEST(LanguageServer, ColumnsAreInTheNegotiatedEncoding) {
  std::string dir = test::scratch("lsp-utf16");
  std::string text = "#version 300 es\n/* \xF0\x9F\x8C\x8D */ uniform mat4 modelMatrix;\nin vec3 position;\n"
                     "void main() { gl_Position = modelMatrix * vec4(position, 1.0); }\n";
  std::string uri = "file://" + dir + "/globe.vert";
  auto open = frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "glsl"}, {"version", 1}, {"text", text}}}}));
  auto column = [&](const Session& s) {
    std::vector<json> published = diagnostics(s);
    if (published.empty()) return -2;
    for (const json& d : published.front()["diagnostics"])
      if (d["code"] == "lwc-uniform-world-float") return d["range"]["start"]["character"].get<int>();
    return -1;
  };
  Session utf16 = serve(frame(initialize()) + open + end_session());
  Session utf8 = serve(frame(initialize({{"general", {{"positionEncodings", {"utf-8", "utf-16"}}}}})) + open + end_session());
  EXPECT_EQ((*reply_to(utf8, 1))["result"]["capabilities"]["positionEncoding"], "utf-8");
  EXPECT_EQ(column(utf16), 3 + 2 + 4 + 13);  // "/* ", the globe (2 units), " */ ", "uniform mat4 "
  EXPECT_EQ(column(utf8), 3 + 4 + 4 + 13);
  // Deleting the globe in UTF-16 units (characters 3 to 5) leaves the finding at column 3 + 4 + 13.
  json remove = {{"range", {{"start", {{"line", 1}, {"character", 3}}}, {"end", {{"line", 1}, {"character", 5}}}}}, {"text", ""}};
  Session edited = serve(frame(initialize()) + open +
                         frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 2}}}, {"contentChanges", {remove}}})) +
                         end_session());
  std::vector<json> published = diagnostics(edited);
  ASSERT_EQ(published.size(), 2u);
  for (const json& d : published[1]["diagnostics"])
    if (d["code"] == "lwc-uniform-world-float") EXPECT_EQ(d["range"]["start"]["character"], 3 + 4 + 13);
}

// Applies LSP text edits (ASCII text: characters are bytes) to a text.
std::string apply(std::string text, const json& edits) {
  std::vector<size_t> starts = {0};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') starts.push_back(i + 1);
  auto at = [&](const json& p) { return starts[p["line"].get<size_t>()] + p["character"].get<size_t>(); };
  std::vector<json> sorted(edits.begin(), edits.end());
  std::sort(sorted.begin(), sorted.end(), [&](const json& a, const json& b) { return at(a["range"]["start"]) > at(b["range"]["start"]); });
  for (const json& e : sorted) {
    size_t begin = at(e["range"]["start"]), end = at(e["range"]["end"]);
    text.replace(begin, end - begin, e["newText"].get<std::string>());
  }
  return text;
}

// Code actions: the quick fix applied gives exactly `lwcport fix`'s file (one finding), fix-all
// gives `lwcport fix`'s file (several), and "ignore for this line" silences the finding.
TEST(LanguageServer, CodeActionsGiveWhatFixGives) {
  std::string dir = test::scratch("lsp-actions");
  std::string text = test::read(test::source_dir() + "/corpus/ue5.4/DoubleFloatHelpers.ush");
  test::write(dir + "/Helpers.ush", text);
  test::Run fixed_run = test::run(test::binary() + " fix " + dir + "/Helpers.ush --fail-on none > /dev/null");
  std::string fixed = test::read(dir + "/Helpers.ush");
  ASSERT_NE(fixed, text);
  std::string uri = "file://" + dir + "/Other.ush";  // not on disk: the text is the client's
  json whole = {{"start", {{"line", 0}, {"character", 0}}}, {"end", {{"line", 200}, {"character", 0}}}};
  // The TwoSum finding (line 21) only: a range on it.
  json on_two_sum = {{"start", {{"line", 20}, {"character", 0}}}, {"end", {{"line", 21}, {"character", 0}}}};
  Session s = serve(frame(initialize()) +
                    frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "hlsl"}, {"version", 1}, {"text", text}}}})) +
                    frame(request(2, "textDocument/codeAction", {{"textDocument", {{"uri", uri}}}, {"range", whole}, {"context", {{"diagnostics", json::array()}}}})) +
                    frame(request(3, "textDocument/codeAction", {{"textDocument", {{"uri", uri}}}, {"range", on_two_sum}, {"context", {{"diagnostics", json::array()}}}})) +
                    end_session());
  const json* all = reply_to(s, 2);
  const json* one = reply_to(s, 3);
  ASSERT_NE(all, nullptr);
  ASSERT_NE(one, nullptr);
  const json* fix_all = nullptr;
  for (const json& a : (*all)["result"])
    if (a["kind"] == "source.fixAll.lwcport") fix_all = &a;
  ASSERT_NE(fix_all, nullptr) << all->dump(2);
  EXPECT_EQ(apply(text, (*fix_all)["edit"]["changes"][uri]), fixed);
  const json *quick = nullptr, *ignore = nullptr;
  for (const json& a : (*one)["result"]) {
    if (a["kind"] == "quickfix" && a.value("isPreferred", false)) quick = &a;
    if (a["title"].get<std::string>().starts_with("ignore lwc-missing-precise")) ignore = &a;
  }
  ASSERT_NE(quick, nullptr) << one->dump(2);
  ASSERT_NE(ignore, nullptr) << one->dump(2);
  // Applied alone, the quick fix makes TwoSumPlain precise, as fix does: fix's file, but for the
  // Split finding the range left out.
  std::string quick_fixed = apply(text, (*quick)["edit"]["changes"][uri]);
  EXPECT_NE(quick_fixed.find("\tprecise float S = A + B;\n\tprecise float V = S - A;"), std::string::npos) << quick_fixed;
  EXPECT_EQ(quick_fixed.find("precise float T = 4097.0f * A;"), std::string::npos);
  std::string ignored = apply(text, (*ignore)["edit"]["changes"][uri]);
  test::write(dir + "/Ignored.ush", ignored);
  json lint = json::parse(test::run(test::binary() + " lint " + dir + "/Ignored.ush --format json --fail-on none").out);
  for (const json& f : lint["findings"]) EXPECT_FALSE(f["rule"] == "lwc-missing-precise" && f["start"]["line"] == 22) << f.dump();
  int missing_precise = 0;
  for (const json& f : lint["findings"]) missing_precise += f["rule"] == "lwc-missing-precise";
  EXPECT_EQ(missing_precise, 1);  // the Split one is still there
}

// The UTF-8 bytes of the character at `at`, and its UTF-16 units: what a client counts.
size_t bytes_at(const std::string& text, size_t at) {
  unsigned char lead = static_cast<unsigned char>(text[at]);
  return lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
}
size_t utf16_units(size_t bytes) { return bytes == 4 ? 2 : 1; }

// The byte offset of a (line, UTF-16 character) position.
size_t byte_offset(const std::string& text, size_t line, size_t character) {
  size_t at = 0;
  for (size_t l = 0; l < line && at < text.size(); ++at)
    if (text[at] == '\n') ++l;
  for (size_t units = 0; at < text.size() && text[at] != '\n' && units < character;) {
    size_t n = bytes_at(text, at);
    units += utf16_units(n);
    at += n;
  }
  return at;
}

// Random edit sequences (seeded): after each batch the server's diagnostics for its copy of the
// text are lint's for the text the client holds, which it built with the same edits (positions in
// UTF-16 units, multi-byte characters and CRLF line ends among the inserted text).
TEST(LanguageServer, RandomEditsKeepDiagnosticsEqualToAFreshLint) {
  std::string dir = test::scratch("lsp-random");
  std::string text = test::read(test::source_dir() + "/corpus/ue4/DeferredLightPixelShaders.usf");
  std::string uri = "file://" + dir + "/Light.usf";
  const std::vector<std::string> pieces = {"float3 WorldPos = View.WorldCameraOrigin;\n", " ", "\r\n", "/* \xC3\xA9 */",
                                           "// \xF0\x9F\x8C\x8D\n", "/* \xF0\x9F\x8C\x8D */", "LightData.Position", ";", "}", "\n\n", ""};
  std::mt19937 random(20261123);
  std::string input = frame(initialize()) +
                      frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "hlsl"}, {"version", 1}, {"text", text}}}}));
  for (int version = 2; version <= 60; ++version) {
    size_t lines = static_cast<size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
    size_t l1 = random() % lines, c1 = random() % 30, l2 = l1 + random() % 2, c2 = random() % 30;
    size_t begin = byte_offset(text, l1, c1), end = byte_offset(text, l2, c2);
    if (end < begin) std::swap(begin, end), std::swap(l1, l2), std::swap(c1, c2);
    // The positions as sent, clamped as the server clamps them, must name these bytes: send the
    // ones recomputed from the bytes (a client never sends a character past a line's end).
    auto units = [&](size_t at) {
      size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
      line_start = (line_start == std::string::npos || at == 0) ? 0 : line_start + 1;
      size_t u = 0;
      for (size_t i = line_start; i < at;) {
        size_t n = bytes_at(text, i);
        u += utf16_units(n);
        i += n;
      }
      return json{{"line", std::count(text.begin(), text.begin() + static_cast<long>(at), '\n')}, {"character", u}};
    };
    std::string piece = pieces[random() % pieces.size()];
    json change = {{"range", {{"start", units(begin)}, {"end", units(end)}}}, {"text", piece}};
    text.replace(begin, end - begin, piece);
    input += frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", version}}}, {"contentChanges", {change}}}));
  }
  Session s = serve(input + end_session());
  std::vector<json> published = diagnostics(s);
  ASSERT_EQ(published.size(), 60u);
  test::write(dir + "/Light.usf", text);
  json lint = json::parse(test::run(test::binary() + " lint " + dir + "/Light.usf --format json --fail-on none").out);
  const json& last = published.back()["diagnostics"];
  ASSERT_EQ(last.size(), lint["findings"].size()) << last.dump(1);
  // lint's columns count code points; the server's, UTF-16 units.
  auto utf16_column = [&](int line, int column) {
    size_t at = byte_offset(text, static_cast<size_t>(line - 1), 0), units = 0;
    for (int cp = 1; cp < column && at < text.size(); ++cp) {
      size_t n = bytes_at(text, at);
      units += utf16_units(n);
      at += n;
    }
    return units;
  };
  for (size_t i = 0; i < last.size(); ++i) {
    const json& f = lint["findings"][i];
    EXPECT_EQ(last[i]["code"], f["rule"]);
    EXPECT_EQ(last[i]["range"]["start"]["line"], f["start"]["line"].get<int>() - 1);
    EXPECT_EQ(last[i]["range"]["start"]["character"], utf16_column(f["start"]["line"], f["start"]["column"]));
  }
}

// Hover on a finding: the rule, its message, summary and rationale, and its page.
TEST(LanguageServer, HoverOnAFindingExplainsTheRule) {
  std::string path = test::source_dir() + "/corpus/glsl/forward.vert";
  std::string uri = "file://" + path;
  Session s = serve(frame(initialize()) +
                    frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "glsl"}, {"version", 1}, {"text", test::read(path)}}}})) +
                    frame(request(2, "textDocument/hover", {{"textDocument", {{"uri", uri}}}, {"position", {{"line", 4}, {"character", 15}}}})) +
                    frame(request(3, "textDocument/hover", {{"textDocument", {{"uri", uri}}}, {"position", {{"line", 0}, {"character", 0}}}})) +
                    end_session());
  const json* on = reply_to(s, 2);
  const json* off = reply_to(s, 3);
  ASSERT_NE(on, nullptr);
  ASSERT_NE(off, nullptr);
  std::string value = (*on)["result"]["contents"]["value"];
  EXPECT_NE(value.find("**lwc-uniform-world-float**"), std::string::npos) << value;
  EXPECT_NE(value.find("docs/rules/lwc-uniform-world-float.md"), std::string::npos) << value;
  EXPECT_TRUE((*off)["result"].is_null());
}

// A changed `.lwcport.json` is read again: the project now ignores the rule, and the open
// document's diagnostics are published again without it. The config changes mid-session, once
// the server has published the first diagnostics (the script waits for them on its output).
TEST(LanguageServer, AChangedConfigIsReadAgain) {
  std::string dir = test::scratch("lsp-config");
  std::string uri = "file://" + dir + "/a.vert";
  std::string text = "#version 300 es\nuniform mat4 modelMatrix;\nin vec3 position;\n"
                     "void main() { gl_Position = modelMatrix * vec4(position, 1.0); }\n";
  test::write(dir + "/.lwcport.json", "{}");
  test::write(dir + "/first", frame(initialize()) +
                                  frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "glsl"}, {"version", 1}, {"text", text}}}})));
  json changed = {{"changes", {{{"uri", "file://" + dir + "/.lwcport.json"}, {"type", 2}}}}};
  test::write(dir + "/then", frame(notification("workspace/didChangeWatchedFiles", changed)) + end_session());
  test::write(dir + "/ignoring.json", R"({"ignore": ["lwc-uniform-world-float", "lwc-float-world-position"]})");
  // (The wait for the first diagnostics is bounded, so a server that never answers fails the test
  // rather than hanging it.)
  test::write(dir + "/session.sh", "set -e\ncd " + dir + "\nmkfifo in\n" + test::binary() + " lsp < in > out &\nserver=$!\n"
                                   "exec 3> in\ncat first >&3\n"
                                   "for i in $(seq 1200); do grep -qs publishDiagnostics out && break; sleep 0.05; done\n"
                                   "cp ignoring.json .lwcport.json\ncat then >&3\nexec 3>&-\nwait $server\n");
  test::run("bash " + dir + "/session.sh");
  std::string out = test::read(dir + "/out");
  std::vector<json> published = diagnostics({0, read_messages(out)});
  ASSERT_EQ(published.size(), 2u) << out;  // the open, and again after the notice
  EXPECT_FALSE(published[0]["diagnostics"].empty());
  EXPECT_TRUE(published[1]["diagnostics"].empty()) << published[1].dump();
}

// A stale change (a version the document already has) is ignored; closing clears the document's
// diagnostics; requests before initialize are refused; exit without shutdown ends with 1.
TEST(LanguageServer, StaleChangesCloseAndLifecycle) {
  std::string dir = test::scratch("lsp-stale");
  std::string uri = "file://" + dir + "/a.vert";
  std::string text = "#version 300 es\nuniform mat4 modelMatrix;\nvoid main() { gl_Position = modelMatrix[3]; }\n";
  json blank = {{"text", "#version 300 es\nvoid main() {}\n"}};
  Session s = serve(frame(request(3, "shutdown")) + frame(initialize()) +
                    frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "glsl"}, {"version", 5}, {"text", text}}}})) +
                    frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 4}}}, {"contentChanges", {blank}}})) +
                    frame(notification("textDocument/didClose", {{"textDocument", {{"uri", uri}}}})) + frame(notification("exit")));
  EXPECT_EQ(s.exit_code, 1);
  const json* early = reply_to(s, 3);
  ASSERT_NE(early, nullptr);
  EXPECT_EQ((*early)["error"]["code"], -32002);
  std::vector<json> published = diagnostics(s);
  ASSERT_EQ(published.size(), 2u);  // the open, then the close; the stale change published nothing
  EXPECT_FALSE(published[0]["diagnostics"].empty());
  EXPECT_TRUE(published[1]["diagnostics"].empty());
}

}  // namespace
}  // namespace lwc
