// `lwcport lsp` driven by scripted JSON-RPC sessions: the framed messages go in on standard input,
// every reply and notification is read back from standard output, in order.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include <nlohmann/json.hpp>

#include "cli/lsp_client.h"
#include "shaderlib/shaderlib.h"
#include "support.h"

namespace lwc {
namespace {

using nlohmann::json;
using namespace lsp_client;


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


json open_document(const std::string& uri, const std::string& language, const std::string& text, int version = 1) {
  return notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", language}, {"version", version}, {"text", text}}}});
}
json whole_range() { return {{"start", {{"line", 0}, {"character", 0}}}, {"end", {{"line", 100000}, {"character", 0}}}}; }

// A client that pulls diagnostics gets none pushed: textDocument/diagnostic answers with lint's
// findings and a result id, "unchanged" for the same id, a new report after an edit; a changed
// config makes the server ask the client to pull again (workspace/diagnostic/refresh).
TEST(LanguageServer, PulledDiagnosticsAndRefresh) {
  std::string path = test::source_dir() + "/corpus/glsl/forward.vert";
  std::string uri = "file://" + path;
  json lint = json::parse(test::run(test::binary() + " lint " + path + " --format json --fail-on none").out);
  json pull_capable = {{"textDocument", {{"diagnostic", json::object()}}}, {"workspace", {{"diagnostics", {{"refreshSupport", true}}}}}};
  json insert = {{"range", {{"start", {{"line", 0}, {"character", 0}}}, {"end", {{"line", 0}, {"character", 0}}}}}, {"text", "// a\n"}};
  auto pull = [&](int id, const std::string& previous) {
    json params = {{"textDocument", {{"uri", uri}}}};
    if (!previous.empty()) params["previousResultId"] = previous;
    return frame(request(id, "textDocument/diagnostic", params));
  };
  Session first = serve(frame(initialize(pull_capable)) + frame(open_document(uri, "glsl", test::read(path))) + pull(2, "") + end_session());
  EXPECT_TRUE(diagnostics(first).empty());
  const json* init = reply_to(first, 1);
  ASSERT_NE(init, nullptr);
  EXPECT_TRUE((*init)["result"]["capabilities"]["diagnosticProvider"]["interFileDependencies"].get<bool>());
  const json* report = reply_to(first, 2);
  ASSERT_NE(report, nullptr);
  EXPECT_EQ((*report)["result"]["kind"], "full");
  ASSERT_EQ((*report)["result"]["items"].size(), lint["findings"].size());
  for (size_t i = 0; i < lint["findings"].size(); ++i) EXPECT_EQ((*report)["result"]["items"][i]["code"], lint["findings"][i]["rule"]);
  std::string id = (*report)["result"]["resultId"];
  Session again = serve(frame(initialize(pull_capable)) + frame(open_document(uri, "glsl", test::read(path))) + pull(2, "") + pull(3, id) +
                        frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 2}}}, {"contentChanges", {insert}}})) +
                        pull(4, id) + frame(notification("workspace/didChangeWatchedFiles", {{"changes", json::array()}})) + end_session());
  EXPECT_EQ((*reply_to(again, 3))["result"]["kind"], "unchanged");
  const json& edited = (*reply_to(again, 4))["result"];
  EXPECT_EQ(edited["kind"], "full");
  EXPECT_NE(edited["resultId"], id);
  EXPECT_EQ(edited["items"][0]["range"]["start"]["line"], (*report)["result"]["items"][0]["range"]["start"]["line"].get<int>() + 1);
  int refreshes = 0;
  for (const json& m : again.messages) refreshes += m.value("method", "") == "workspace/diagnostic/refresh" && m.contains("id");
  EXPECT_EQ(refreshes, 1);
}

// A client that resolves code actions lazily gets them without edits, each with data; resolving
// gives the edit the eager path gives. A resolve for a version the document no longer has is
// refused (ContentModified). workspace/executeCommand lwcport.fixAll sends the client, as
// workspace/applyEdit, exactly `lwcport fix`'s file.
TEST(LanguageServer, LazyCodeActionsAndTheFixAllCommand) {
  std::string dir = test::scratch("lsp-lazy");
  std::string text = test::read(test::source_dir() + "/corpus/ue5.4/DoubleFloatHelpers.ush");
  test::write(dir + "/Helpers.ush", text);
  test::run(test::binary() + " fix " + dir + "/Helpers.ush --fail-on none > /dev/null");
  std::string fixed = test::read(dir + "/Helpers.ush");
  std::string uri = "file://" + dir + "/Open.ush";
  json lazy = {{"textDocument", {{"codeAction", {{"resolveSupport", {{"properties", {"edit"}}}}}}}}};
  auto actions = frame(request(2, "textDocument/codeAction", {{"textDocument", {{"uri", uri}}}, {"range", whole_range()}, {"context", {{"diagnostics", json::array()}}}}));
  Session eager = serve(frame(initialize()) + frame(open_document(uri, "hlsl", text)) + actions + end_session());
  Session first = serve(frame(initialize(lazy)) + frame(open_document(uri, "hlsl", text)) + actions + end_session());
  const json& eager_actions = (*reply_to(eager, 2))["result"];
  const json& lazy_actions = (*reply_to(first, 2))["result"];
  ASSERT_EQ(lazy_actions.size(), eager_actions.size());
  ASSERT_FALSE(lazy_actions.empty());
  std::string resolves;
  for (size_t i = 0; i < lazy_actions.size(); ++i) {
    EXPECT_FALSE(lazy_actions[i].contains("edit"));
    EXPECT_TRUE(lazy_actions[i]["data"].is_object());
    resolves += frame(request(10 + static_cast<int>(i), "codeAction/resolve", lazy_actions[i]));
  }
  json blank = {{"text", "\n" + text}};
  Session resolved = serve(frame(initialize(lazy)) + frame(open_document(uri, "hlsl", text)) + resolves +
                           frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 2}}}, {"contentChanges", {blank}}})) +
                           frame(request(50, "codeAction/resolve", lazy_actions[0])) +
                           frame(request(51, "workspace/executeCommand", {{"command", "lwcport.fixAll"}, {"arguments", {uri}}})) + end_session());
  for (size_t i = 0; i < lazy_actions.size(); ++i) {
    const json* r = reply_to(resolved, 10 + static_cast<int>(i));
    ASSERT_NE(r, nullptr);
    EXPECT_EQ((*r)["result"]["edit"], eager_actions[i]["edit"]) << (*r).dump();
  }
  EXPECT_EQ((*reply_to(resolved, 50))["error"]["code"], -32801);
  EXPECT_TRUE((*reply_to(resolved, 51))["result"].is_null());
  const json* apply_edit = nullptr;
  for (const json& m : resolved.messages)
    if (m.value("method", "") == "workspace/applyEdit") apply_edit = &m;
  ASSERT_NE(apply_edit, nullptr);
  EXPECT_EQ(apply("\n" + text, (*apply_edit)["params"]["edit"]["changes"][uri]), "\n" + fixed);
}

// A request cancelled while it waits is answered RequestCancelled (the server is busy analysing a
// long document when both arrive); the next request is answered. --log writes each message and
// analysis; window/logMessage says what the server serves.
TEST(LanguageServer, CancellationAndLogging) {
  std::string dir = test::scratch("lsp-cancel");
  std::string unit = test::read(test::source_dir() + "/corpus/ue4/DeferredLightPixelShaders.usf");
  std::string big;
  for (int i = 0; i < 60; ++i) big += unit;  // long enough to analyse for a while
  std::string uri = "file://" + dir + "/Big.usf";
  json hover = {{"textDocument", {{"uri", uri}}}, {"position", {{"line", 0}, {"character", 0}}}};
  Session s = serve(frame(initialize()) + frame(open_document(uri, "hlsl", big)) + frame(request(5, "textDocument/hover", hover)) +
                        frame(notification("$/cancelRequest", {{"id", 5}})) + frame(request(6, "textDocument/hover", hover)) + end_session(),
                    "--log " + dir + "/server.log");
  const json* cancelled = reply_to(s, 5);
  ASSERT_NE(cancelled, nullptr);
  EXPECT_EQ((*cancelled)["error"]["code"], -32800);
  const json* answered = reply_to(s, 6);
  ASSERT_NE(answered, nullptr);
  EXPECT_FALSE(answered->contains("error"));
  std::vector<json> logged = notifications(s, "window/logMessage");
  ASSERT_FALSE(logged.empty());
  EXPECT_NE(logged[0]["message"].get<std::string>().find("UTF-16"), std::string::npos);
  std::string log = test::read(dir + "/server.log");
  for (const char* line : {"<- initialize (1)", "<- textDocument/didOpen", "analysed ", "cancelled (5)", "<- exit"})
    EXPECT_NE(log.find(line), std::string::npos) << line << "\n" << log;
}

// A document that starts with a byte-order mark: the mark is the first character of line 0, as the
// client counts it, and the findings are where lint puts them.
TEST(LanguageServer, ADocumentWithAByteOrderMark) {
  std::string text = "\xEF\xBB\xBFuniform mat4 modelMatrix;\nin vec3 position;\nvoid main() { gl_Position = modelMatrix * vec4(position, 1.0); }\n";
  std::string dir = test::scratch("lsp-bom");
  Session s = serve(frame(initialize()) + frame(open_document("file://" + dir + "/a.vert", "glsl", text)) + end_session());
  std::vector<json> published = diagnostics(s);
  ASSERT_EQ(published.size(), 1u);
  bool found = false;
  for (const json& d : published[0]["diagnostics"])
    if (d["code"] == "lwc-uniform-world-float") {
      found = true;
      EXPECT_EQ(d["range"]["start"], json({{"line", 0}, {"character", 1 + 13}}));  // the mark, then "uniform mat4 "
    }
  EXPECT_TRUE(found) << published[0].dump();
}

// Diagnostics are written as JSON text directly: their messages (hints after a line break,
// backticks) are `lint --format json`'s, in a document with quotes, tabs and control characters.
TEST(LanguageServer, DiagnosticMessagesAreLintsMessages) {
  std::string text = "// caf\u00e9 \"quoted\"\t\x01 \\ \U0001F600\nuniform mat4 modelMatrix;\nin vec3 position;\n"
                     "void main() { gl_Position = modelMatrix * vec4(position, 1.0); }\n";
  std::string dir = test::scratch("lsp-json-text");
  test::write(dir + "/a.vert", text);
  json lint = json::parse(test::run(test::binary() + " lint " + dir + "/a.vert --format json --fail-on none").out);
  Session s = serve(frame(initialize()) + frame(open_document("file://" + dir + "/a.vert", "glsl", text)) + end_session());
  std::vector<json> published = diagnostics(s);
  ASSERT_EQ(published.size(), 1u);
  ASSERT_EQ(published[0]["diagnostics"].size(), lint["findings"].size());
  ASSERT_FALSE(lint["findings"].empty());
  for (size_t i = 0; i < lint["findings"].size(); ++i) {
    const json &d = published[0]["diagnostics"][i], &f = lint["findings"][i];
    std::string hint = f.value("hint", "");
    EXPECT_EQ(d["message"], f["message"].get<std::string>() + (hint.empty() ? "" : "\n" + hint));
    EXPECT_EQ(d["range"]["start"]["line"], f["start"]["line"].get<int>() - 1);
  }
}

// An open include is what its includers see: editing it (here, so that its function no longer
// returns an absolute position) analyses the open file that includes it again, with the new text,
// before anything is saved.
TEST(LanguageServer, AnEditedIncludeIsReadFromTheEditor) {
  std::string dir = test::scratch("lsp-include");
  std::string header = "float3 GetCameraPos()\n{\n\treturn View.WorldCameraOrigin;\n}\n";
  std::string user = "#include \"A.ush\"\n\nfloat3 F(float3 Offset)\n{\n\tfloat3 P = GetCameraPos();\n\treturn P - Offset;\n}\n";
  test::write(dir + "/A.ush", header);
  test::write(dir + "/B.usf", user);
  std::string a = "file://" + dir + "/A.ush", b = "file://" + dir + "/B.usf";
  json small = {{"range", {{"start", {{"line", 2}, {"character", 8}}}, {"end", {{"line", 2}, {"character", 29}}}}}, {"text", "float3(0, 0, 0)"}};
  Session s = serve(frame(initialize()) + frame(open_document(a, "hlsl", header)) + frame(open_document(b, "hlsl", user)) +
                    frame(notification("textDocument/didChange", {{"textDocument", {{"uri", a}, {"version", 2}}}, {"contentChanges", {small}}})) +
                    end_session());
  std::vector<json> for_b;
  for (const json& p : diagnostics(s))
    if (p["uri"] == b) for_b.push_back(p["diagnostics"]);
  ASSERT_EQ(for_b.size(), 2u);  // on open, and again after the include's edit
  EXPECT_EQ(for_b[0].size(), 2u) << for_b[0].dump();
  EXPECT_TRUE(for_b[1].empty()) << for_b[1].dump();
  EXPECT_EQ(test::read(dir + "/A.ush"), header);  // nothing was written
}

// Hover anywhere on a value: its world-space kind and where it came from, step by step; a finding's
// diagnostic carries the same trail as related information.
TEST(LanguageServer, HoverShowsAValuesKindAndProvenance) {
  std::string path = test::source_dir() + "/corpus/glsl/forward.vert";
  std::string uri = "file://" + path;
  // Line 17 (0-based 16): `vec4 worldPosition = modelMatrix * vec4(position, 1.0);`; line 19 uses it.
  Session s = serve(frame(initialize()) + frame(open_document(uri, "glsl", test::read(path))) +
                    frame(request(2, "textDocument/hover", {{"textDocument", {{"uri", uri}}}, {"position", {{"line", 17}, {"character", 20}}}})) +
                    end_session());
  const json* hover = reply_to(s, 2);
  ASSERT_NE(hover, nullptr);
  std::string value = (*hover)["result"]["contents"]["value"];
  EXPECT_NE(value.find("`worldPosition`: an absolute world position"), std::string::npos) << value;
  EXPECT_NE(value.find("`worldPosition` = `modelMatrix * vec4(position, 1.0)` (line 17)"), std::string::npos) << value;
  EXPECT_NE(value.find("`mat4 modelMatrix`, a global (line 5)"), std::string::npos) << value;
  std::vector<json> published = diagnostics(s);
  ASSERT_EQ(published.size(), 1u);
  const json* world_position = nullptr;
  for (const json& d : published[0]["diagnostics"])
    if (d["code"] == "lwc-float-world-position" && d["range"]["start"]["line"] == 16) world_position = &d;
  ASSERT_NE(world_position, nullptr);
  const json& related = (*world_position)["relatedInformation"];
  ASSERT_EQ(related.size(), 2u) << related.dump();
  EXPECT_EQ(related[1]["location"]["range"]["start"]["line"], 4);  // the uniform's declaration
  EXPECT_EQ(related[1]["location"]["uri"], uri);
}

// A rewrite that calls lwcport's DoubleFloat library, for a client that can create files: the
// quick fix creates the library beside the document with what the rewrite calls, and "fix all"
// (unsafe fixes on, through workspace/applyEdit) gives the document and library `lwcport fix
// --unsafe-fixes` writes. A client that cannot create files is not offered the rewrite.
TEST(LanguageServer, ARewriteThatNeedsTheLibraryCreatesIt) {
  std::string dir = test::scratch("lsp-library");
  std::string text = test::read(test::source_dir() + "/corpus/glsl/forward.vert");
  test::write(dir + "/cli/forward.vert", text);
  test::run(test::binary() + " fix " + dir + "/cli/forward.vert --unsafe-fixes --fail-on none > /dev/null");
  std::string fixed = test::read(dir + "/cli/forward.vert"), library = test::read(dir + "/cli/lwc_doublefloat.glsl");
  std::string uri = "file://" + dir + "/editor/forward.vert", library_uri = "file://" + dir + "/editor/lwc_doublefloat.glsl";
  json creates = {{"workspace", {{"workspaceEdit", {{"documentChanges", true}, {"resourceOperations", {"create"}}}}}}};
  // Line 17 (0-based 16): `vec4 worldPosition = modelMatrix * vec4(position, 1.0);`
  json on_it = {{"start", {{"line", 16}, {"character", 0}}}, {"end", {{"line", 16}, {"character", 10}}}};
  auto actions = frame(request(2, "textDocument/codeAction", {{"textDocument", {{"uri", uri}}}, {"range", on_it}, {"context", {{"diagnostics", json::array()}}}}));
  auto init = [&](const json& capabilities) {
    return frame(request(1, "initialize", {{"capabilities", capabilities}, {"initializationOptions", {{"unsafeFixes", true}}}}));
  };
  Session s = serve(init(creates) + frame(open_document(uri, "glsl", text)) + actions +
                    frame(request(3, "workspace/executeCommand", {{"command", "lwcport.fixAll"}, {"arguments", {uri}}})) + end_session());
  Session without = serve(init(json::object()) + frame(open_document(uri, "glsl", text)) + actions + end_session());
  const json* with_library = nullptr;
  for (const json& a : (*reply_to(s, 2))["result"])
    if (a["edit"].contains("documentChanges")) with_library = &a;
  ASSERT_NE(with_library, nullptr) << reply_to(s, 2)->dump(1);
  for (const json& a : (*reply_to(without, 2))["result"]) EXPECT_NE(a["title"], (*with_library)["title"]) << "offered without create: " << a.dump();
  // Applies document changes to the texts by URI (a created file starts empty).
  auto apply_changes = [&](const json& changes) {
    std::map<std::string, std::string> files = {{uri, text}};
    for (const json& c : changes) {
      if (c.value("kind", "") == "create") {
        files[c["uri"]] = "";
        continue;
      }
      std::string target = c["textDocument"]["uri"];
      files[target] = apply(files.at(target), c["edits"]);
    }
    return files;
  };
  const json& changes = (*with_library)["edit"]["documentChanges"];
  EXPECT_EQ(changes[0]["kind"], "create");
  std::map<std::string, std::string> quick = apply_changes(changes);
  EXPECT_TRUE(is_written_library(quick.at(library_uri)));
  EXPECT_NE(quick.at(uri).find("#include \"lwc_doublefloat.glsl\""), std::string::npos);
  const json* apply_edit = nullptr;
  for (const json& m : s.messages)
    if (m.value("method", "") == "workspace/applyEdit") apply_edit = &m;
  ASSERT_NE(apply_edit, nullptr);
  std::map<std::string, std::string> all = apply_changes((*apply_edit)["params"]["edit"]["documentChanges"]);
  EXPECT_EQ(all.at(uri), fixed);
  EXPECT_EQ(all.at(library_uri), library);
}

// A lone "\r" ends a line as LSP counts lines (as "\n" and "\r\n" do): positions after it, and edits
// given in them, land where the client means.
TEST(LanguageServer, ALoneCarriageReturnEndsALine) {
  std::string text = "/* old Mac line end */\runiform mat4 modelMatrix;\nin vec3 position;\n"
                     "void main() { gl_Position = modelMatrix * vec4(position, 1.0); }\n";
  std::string uri = "file://" + test::scratch("lsp-cr") + "/a.vert";
  json indent = {{"range", {{"start", {{"line", 1}, {"character", 0}}}, {"end", {{"line", 1}, {"character", 0}}}}}, {"text", "  "}};
  json at_end = {{"range", {{"start", {{"line", 0}, {"character", 22}}}, {"end", {{"line", 0}, {"character", 99}}}}}, {"text", " /**/"}};
  Session s = serve(frame(initialize()) + frame(open_document(uri, "glsl", text)) +
                    frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", 2}}}, {"contentChanges", {indent, at_end}}})) +
                    end_session());
  std::vector<json> published = diagnostics(s);
  ASSERT_EQ(published.size(), 2u);
  auto start_of = [](const json& p) {
    for (const json& d : p["diagnostics"])
      if (d["code"] == "lwc-uniform-world-float") return d["range"]["start"];
    return json();
  };
  EXPECT_EQ(start_of(published[0]), json({{"line", 1}, {"character", 13}}));
  // The indent moved it by two; the comment went before the lone "\r" (the range's end past the
  // line is the line's end), so the line did not grow by five.
  EXPECT_EQ(start_of(published[1]), json({{"line", 1}, {"character", 15}}));
}

// A CRLF document: the quick fixes and fix-all keep its line ends (fix-all gives exactly what
// `lwcport fix` writes for the CRLF file), and "ignore for this line" inserts a CRLF line.
TEST(LanguageServer, ACrlfDocumentKeepsItsLineEnds) {
  std::string dir = test::scratch("lsp-crlf");
  std::string lf = test::read(test::source_dir() + "/corpus/ue5.4/DoubleFloatHelpers.ush"), text;
  for (char c : lf) text += c == '\n' ? std::string("\r\n") : std::string(1, c);
  test::write(dir + "/cli/Helpers.ush", text);
  test::run(test::binary() + " fix " + dir + "/cli/Helpers.ush --fail-on none > /dev/null");
  std::string fixed = test::read(dir + "/cli/Helpers.ush");
  ASSERT_NE(fixed, text);
  std::string uri = "file://" + dir + "/editor/Helpers.ush";
  Session s = serve(frame(initialize()) + frame(open_document(uri, "hlsl", text)) +
                    frame(request(2, "textDocument/codeAction", {{"textDocument", {{"uri", uri}}}, {"range", whole_range()}, {"context", {{"diagnostics", json::array()}}}})) +
                    end_session());
  const json* actions = reply_to(s, 2);
  ASSERT_NE(actions, nullptr);
  bool fix_all = false, ignore = false;
  for (const json& a : (*actions)["result"]) {
    std::string applied = lsp_client::apply(text, a["edit"]["changes"][uri]);
    EXPECT_EQ(applied.find("\n"), applied.find("\r\n") + 1) << a["title"];  // no bare LF came in
    size_t lf_count = std::count(applied.begin(), applied.end(), '\n'), cr_count = std::count(applied.begin(), applied.end(), '\r');
    EXPECT_EQ(lf_count, cr_count) << a["title"];
    if (a["kind"] == "source.fixAll.lwcport") {
      fix_all = true;
      EXPECT_EQ(applied, fixed);
    }
    if (a["title"].get<std::string>().starts_with("ignore ")) ignore = true;
  }
  EXPECT_TRUE(fix_all);
  EXPECT_TRUE(ignore);
}

// Hover on an #include line says where it resolves, or where lwcport looked when it does not.
TEST(LanguageServer, HoverOnAnIncludeSaysWhereItResolves) {
  std::string dir = test::scratch("lsp-include-hover");
  test::write(dir + "/A.ush", "float3 F() { return float3(0, 0, 0); }\n");
  std::string text = "#include \"A.ush\"\n#include \"/Engine/Private/Common.ush\"\nfloat3 G() { return F(); }\n";
  std::string uri = "file://" + dir + "/B.usf";
  auto hover_at = [&](int id, int line) {
    return frame(request(id, "textDocument/hover", {{"textDocument", {{"uri", uri}}}, {"position", {{"line", line}, {"character", 3}}}}));
  };
  Session s = serve(frame(initialize()) + frame(open_document(uri, "hlsl", text)) + hover_at(2, 0) + hover_at(3, 1) + end_session());
  std::string found = (*reply_to(s, 2))["result"]["contents"]["value"], missing = (*reply_to(s, 3))["result"]["contents"]["value"];
  EXPECT_EQ(found, "`A.ush` resolves to `" + dir + "/A.ush`");
  EXPECT_NE(missing.find("`/Engine/Private/Common.ush` is not found: lwcport looked beside the file"), std::string::npos) << missing;
  EXPECT_NE(missing.find("\"virtual-roots\""), std::string::npos) << missing;
  EXPECT_EQ((*reply_to(s, 3))["result"]["range"]["end"], json({{"line", 1}, {"character", 37}}));  // the whole directive
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
