// The language server under random editing: 10,000 seeded edit sequences on corpus files, each
// ending at a checkpoint (a request on the document), keep every diagnostic the server publishes
// equal to a fresh analysis of the text the client holds at that version, as `lint` runs it
// (ranges, words, related places and what resolving its fixes needs).
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <set>
#include <random>

#include "cli/lsp_client.h"
#include "project/config.h"
#include "project/includes.h"
#include "rules/analyze.h"

namespace lwc {
namespace {

using namespace lsp_client;

// What `lint` finds in `text` at `path`: its project's options and its includes, as the command
// line reads them.
std::vector<Finding> fresh_lint(const std::string& path, const std::string& text) {
  ConfigFinder configs;
  IncludeSummaries includes;
  std::shared_ptr<const ProjectConfig> config = configs.for_dir(std::filesystem::path(path).parent_path());
  AnalyzeOptions options = analysis_options(*config);
  FileSummary summary = includes.for_file(path, text, *config);
  options.includes = &summary;
  return analyze(Source(path, text), options);
}

// The diagnostic a client should see for the finding `index` of `text` at `version`.
json expected_diagnostic(const std::string& text, const Finding& f, int version, size_t index) {
  auto range = [&](Span span) { return json{{"start", position_of(text, span.begin)}, {"end", position_of(text, span.end)}}; };
  json related = json::array();
  for (const auto& [span, message] : f.related) related.push_back({{"range", range(span)}, {"message", message}});
  return {{"code", f.rule},
          {"severity", f.severity == Severity::error ? 1 : f.severity == Severity::warning ? 2 : 3},
          {"message", f.hint.empty() ? f.message : f.message + "\n" + f.hint},
          {"range", range(f.span)},
          {"related", related},
          {"data", {{"version", version}, {"finding", index}, {"fixes", f.fixes.size()}}}};
}

// What a published diagnostic says about where its value came from, as expected_diagnostic has it.
json related_of(const json& diagnostic) {
  json out = json::array();
  for (const json& r : diagnostic.value("relatedInformation", json::array())) out.push_back({{"range", r["location"]["range"]}, {"message", r["message"]}});
  return out;
}

TEST(LanguageServerFuzz, TenThousandEditSequencesKeepDiagnosticsEqualToAFreshLint) {
  const std::vector<std::pair<std::string, std::string>> files = {
      {"corpus/glsl/forward.vert", "glsl"}, {"corpus/ue4/DeferredLightPixelShaders.usf", "hlsl"}, {"corpus/d3d/Terrain.hlsl", "hlsl"},
      {"corpus/ue5.4/DoubleFloatHelpers.ush", "hlsl"}, {"corpus/glsl/SunAndFog.frag", "glsl"}};
  const std::vector<std::string> pieces = {"float3 WorldPos = View.WorldCameraOrigin;\n", " ", "\r\n", "/* \xC3\xA9 */", "// \xF0\x9F\x8C\x8D\n",
                                           "/* \xF0\x9F\x8C\x8D */", "LightData.Position", ";", "}", "{", "(", "\n\n", "#if A\n", "#endif\n",
                                           "uniform mat4 modelMatrix;\n", "precise ", "// lwcport-ignore: lwc-float-world-position\n", ""};
  std::mt19937 random(20261123);
  const int kSessions = 20, kSequences = 500;
  int checkpoints = 0, compared = 0;
  for (int session = 0; session < kSessions; ++session) {
    const auto& [file, language] = files[session % files.size()];
    std::string original = test::read(test::source_dir() + "/" + file);
    std::string dir = test::scratch("lsp-fuzz-" + std::to_string(session));
    std::string path = dir + "/" + std::filesystem::path(file).filename().string();
    std::string uri = "file://" + path;
    std::string text = original;
    std::map<int, std::string> texts = {{1, text}};  // version -> the client's text
    std::vector<int> checkpoint_versions;
    std::string input = frame(initialize()) +
                        frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", language}, {"version", 1}, {"text", text}}}}));
    int version = 1;
    for (int sequence = 0; sequence < kSequences; ++sequence) {
      int edits = 1 + static_cast<int>(random() % 4);
      for (int e = 0; e < edits; ++e) {
        json change;
        if (random() % 200 == 0) {  // now and then the whole text, as a client without ranges sends it
          text = original;
          change = {{"text", text}};
        } else {
          size_t lines = static_cast<size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
          size_t l1 = random() % lines, c1 = random() % 40, l2 = l1 + random() % 2, c2 = random() % 40;
          size_t begin = byte_offset(text, l1, c1), end = byte_offset(text, l2, c2);
          if (end < begin) std::swap(begin, end);
          std::string piece = pieces[random() % pieces.size()];
          change = {{"range", {{"start", position_of(text, begin)}, {"end", position_of(text, end)}}}, {"text", piece}};
          text.replace(begin, end - begin, piece);
        }
        texts[++version] = text;
        input += frame(notification("textDocument/didChange", {{"textDocument", {{"uri", uri}, {"version", version}}}, {"contentChanges", {change}}}));
      }
      // The checkpoint: a request on the document, which it answers from an analysis of this version.
      json range = {{"start", {{"line", 0}, {"character", 0}}}, {"end", {{"line", 0}, {"character", 0}}}};
      input += frame(request(1000 + sequence, "textDocument/codeAction",
                             {{"textDocument", {{"uri", uri}}}, {"range", range}, {"context", {{"diagnostics", json::array()}, {"only", {"quickfix"}}}}}));
      checkpoint_versions.push_back(version);
    }
    Session s = serve_here(input + end_session());
    ASSERT_EQ(s.exit_code, 0);
    std::set<int> published_versions;
    for (const json& published : diagnostics(s)) {
      int v = published["version"];
      published_versions.insert(v);
      const std::string& at = texts.at(v);
      std::vector<Finding> findings = fresh_lint(path, at);
      const json& got = published["diagnostics"];
      ASSERT_EQ(got.size(), findings.size()) << file << " version " << v << ":\n" << at;
      for (size_t i = 0; i < findings.size(); ++i) {
        json want = expected_diagnostic(at, findings[i], v, i);
        for (const char* key : {"code", "severity", "message", "range", "data"}) ASSERT_EQ(got[i][key], want[key]) << file << " version " << v << ", " << key;
        ASSERT_EQ(related_of(got[i]), want["related"]) << file << " version " << v;
      }
      ++compared;
    }
    for (int v : checkpoint_versions) EXPECT_TRUE(published_versions.count(v)) << file << ": no diagnostics for checkpoint version " << v;
    checkpoints += static_cast<int>(checkpoint_versions.size());
  }
  EXPECT_EQ(checkpoints, kSessions * kSequences);
  EXPECT_GE(compared, checkpoints);
}

// Random messages: known methods with parameters of the wrong shape (missing members, wrong types,
// negative and huge positions, unknown documents), random ids, bytes that are not JSON and headers
// that lie. The server never stops early, and answers every request it reads exactly once.
TEST(LanguageServerFuzz, RandomMessagesAreAnsweredAndNeverStopTheServer) {
  const std::vector<std::string> methods = {"textDocument/didOpen", "textDocument/didChange", "textDocument/didClose", "textDocument/didSave",
                                            "textDocument/codeAction", "codeAction/resolve", "textDocument/hover", "textDocument/diagnostic",
                                            "workspace/executeCommand", "workspace/didChangeConfiguration", "$/cancelRequest", "no/such"};
  std::string uri = "file://" + test::scratch("lsp-messages") + "/a.usf";
  std::string text = test::read(test::source_dir() + "/corpus/ue4/HeightFogCommon.ush");
  std::mt19937 random(7);
  auto any_value = [&](int depth) {
    std::function<json(int)> make = [&](int d) -> json {
      switch (random() % (d > 2 ? 6 : 9)) {
        case 0: return nullptr;
        case 1: return static_cast<int>(random() % 5) - 2;
        case 2: return 1e300;
        case 3: return std::string(random() % 3, 'x');
        case 4: return uri;
        case 5: return random() % 2 == 0;
        case 6: return json::array({make(d + 1), make(d + 1)});
        case 7: return {{"line", make(d + 1)}, {"character", make(d + 1)}};
        default: return {{"uri", uri}, {"start", make(d + 1)}, {"range", make(d + 1)}, {"text", make(d + 1)}, {"version", make(d + 1)}};
      }
    };
    return make(depth);
  };
  std::string input = frame(initialize()) +
                      frame(notification("textDocument/didOpen", {{"textDocument", {{"uri", uri}, {"languageId", "hlsl"}, {"version", 1}, {"text", text}}}}));
  std::set<int> asked;
  std::map<int, std::string> requests;
  for (int i = 0; i < 3000; ++i) {
    switch (random() % 10) {
      case 0: input += "Content-Length: 7\r\n\r\n{\"a\":[}"; continue;
      case 1: input += "X-Nothing: 1\r\n\r\n"; continue;
      default: break;
    }
    std::string method = methods[random() % methods.size()];
    json params = {{"textDocument", random() % 4 ? json{{"uri", uri}, {"version", static_cast<int>(random() % 50)}} : any_value(0)},
                   {"position", any_value(1)}, {"range", random() % 2 ? json{{"start", any_value(1)}, {"end", any_value(1)}} : any_value(0)},
                   {"contentChanges", random() % 2 ? json::array({any_value(0)}) : any_value(0)}, {"context", any_value(0)},
                   {"data", any_value(0)}, {"command", random() % 2 ? json("lwcport.fixAll") : any_value(0)},
                   {"arguments", json::array({any_value(0)})}, {"id", any_value(0)}};
    if (random() % 3 == 0) params = any_value(0);
    bool is_request = random() % 2 == 0;
    if (is_request) {
      asked.insert(1000 + i);
      requests[1000 + i] = request(1000 + i, method, params).dump();
      input += frame(request(1000 + i, method, params));
    } else {
      input += frame(notification(method, params));
    }
  }
  Session s = serve_here(input + end_session());
  EXPECT_EQ(s.exit_code, 0);
  std::map<int, int> answers;
  for (const json& m : s.messages)
    if (m.contains("id") && m["id"].is_number_integer() && !m.contains("method")) ++answers[m["id"].get<int>()];
  for (int id : asked) EXPECT_EQ(answers[id], 1) << "request " << id << ": " << requests[id];
  EXPECT_EQ(answers[99], 1);  // the shutdown at the end: the server was still there
}

}  // namespace
}  // namespace lwc
