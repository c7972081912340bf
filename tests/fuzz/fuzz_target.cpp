// libFuzzer target: any bytes as a shader file (the first byte picks the extension, so every
// language and container is reached) through analyze, fix_source with unsafe fixes, and every
// output format, and the verifier's text stage (the harness kernel of the first function with a
// finding, as written and promoted to double). A first byte of 0xF0 or more instead opens the rest
// in the language server and edits, hovers and asks for code actions at positions the bytes pick
// (the server's position and edit arithmetic on any text). Built with ASan and UBSan
// (tests/fuzz/build.sh); a crash, an uncaught exception, invalid JSON output, a finding outside the
// file or a hang is a bug.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/report.h"
#include "fix/apply.h"
#include "lsp/server.h"
#include "rules/analyze.h"
#include "verify/kernel_builder.h"

namespace {

const char* const kPaths[] = {"fuzz.usf", "fuzz.ush", "fuzz.hlsl", "fuzz.vert", "fuzz.frag", "fuzz.comp", "fuzz.glsl.js", "fuzz.sc"};

void check(bool ok) {
  if (!ok) std::abort();
}

std::string frame(const nlohmann::json& message) {
  std::string body = message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

// The text opened in the language server, then, per byte pair of its first 64 bytes, an edit, a
// hover or a code action at a position they pick (lines and characters past the ends too).
void serve(const uint8_t* data, size_t size) {
  using nlohmann::json;
  std::string text(reinterpret_cast<const char*>(data), size);
  std::string uri = std::string("file:///fuzz/fuzz.") + (size % 2 ? "usf" : "vert");
  std::string input = frame({{"jsonrpc", "2.0"}, {"id", 1}, {"method", "initialize"}, {"params", {{"capabilities", json::object()}}}}) +
                      frame({{"jsonrpc", "2.0"}, {"method", "textDocument/didOpen"},
                             {"params", {{"textDocument", {{"uri", uri}, {"languageId", ""}, {"version", 1}, {"text", text}}}}}});
  int version = 1;
  for (size_t i = 0; i + 1 < std::min<size_t>(size, 64); i += 2) {
    json position = {{"line", data[i] % 16}, {"character", data[i + 1] % 48}};
    json range = {{"start", position}, {"end", {{"line", data[i] % 16 + data[i + 1] % 2}, {"character", data[i] % 8}}}};
    json document = {{"uri", uri}};
    switch (data[i] % 4) {
      case 0:
        input += frame({{"jsonrpc", "2.0"}, {"method", "textDocument/didChange"},
                        {"params", {{"textDocument", {{"uri", uri}, {"version", ++version}}},
                                    {"contentChanges", {{{"range", range}, {"text", std::string(1, static_cast<char>(data[i + 1]))}}}}}}});
        break;
      case 1:
        input += frame({{"jsonrpc", "2.0"}, {"id", 100 + i}, {"method", "textDocument/hover"}, {"params", {{"textDocument", document}, {"position", position}}}});
        break;
      default:
        input += frame({{"jsonrpc", "2.0"}, {"id", 100 + i}, {"method", "textDocument/codeAction"},
                        {"params", {{"textDocument", document}, {"range", range}, {"context", {{"diagnostics", json::array()}}}}}});
    }
  }
  input += frame({{"jsonrpc", "2.0"}, {"id", 2}, {"method", "shutdown"}}) + frame({{"jsonrpc", "2.0"}, {"method", "exit"}});
  std::istringstream in(input);
  std::ostringstream out;
  check(lwc::run_language_server(in, out) == 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  if (data[0] >= 0xF0) {
    serve(data + 1, size - 1);
    return 0;
  }
  std::string path = kPaths[data[0] % (sizeof kPaths / sizeof kPaths[0])];
  lwc::Source source(path, std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  lwc::AnalyzeOptions options;
  lwc::FileReport report{path, {}};
  std::vector<uint32_t> offsets;
  for (const lwc::Finding& f : lwc::analyze(source, options)) {
    check(f.span.begin <= f.span.end && f.span.end <= source.text().size());
    offsets.push_back(f.span.begin);
    report.findings.push_back(lwc::locate(source, f));
  }
  // The verifier cuts a kernel out of the text without a device: that part is fuzzed too.
  if (!path.ends_with(".js")) {
    lwc::Lang lang = path.ends_with(".usf") || path.ends_with(".ush") || path.ends_with(".hlsl") ? lwc::Lang::hlsl : lwc::Lang::glsl;
    for (const std::string& function : lwc::enclosing_functions(lang, source.text(), offsets))
      if (!function.empty()) {
        lwc::build_harness_kernel(lang, source.text(), function, false);
        lwc::build_harness_kernel(lang, lwc::promote_to_double(lang, source.text()), function, true);
        break;
      }
  }
  lwc::FixOutcome fixed = lwc::fix_source(source, options, /*unsafe=*/true);
  lwc::Source result(path, fixed.text);
  for (const lwc::Finding& f : fixed.remaining) check(f.span.end <= result.text().size());
  for (lwc::Format format : {lwc::Format::text, lwc::Format::json, lwc::Format::sarif, lwc::Format::github}) {
    std::ostringstream out;
    lwc::ReportOptions ro;
    ro.format = format;
    ro.working_dir = "/fuzz";
    lwc::ReportWriter writer(out, ro);
    writer.file(report);
    writer.finish();
    if (format == lwc::Format::json || format == lwc::Format::sarif) check(nlohmann::json::accept(out.str()));
  }
  return 0;
}
