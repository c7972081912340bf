// libFuzzer target: any bytes as a shader file (the first byte picks the extension, so every
// language and container is reached) through analyze, fix_source with unsafe fixes, and every
// output format. Built with ASan and UBSan (tests/fuzz/build.sh); a crash, an uncaught exception,
// invalid JSON output, a finding outside the file or a hang is a bug.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/report.h"
#include "fix/apply.h"
#include "rules/analyze.h"

namespace {

const char* const kPaths[] = {"fuzz.usf", "fuzz.ush", "fuzz.hlsl", "fuzz.vert", "fuzz.frag", "fuzz.comp", "fuzz.glsl.js", "fuzz.sc"};

void check(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::string path = kPaths[data[0] % (sizeof kPaths / sizeof kPaths[0])];
  lwc::Source source(path, std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  lwc::AnalyzeOptions options;
  lwc::FileReport report{path, {}};
  for (const lwc::Finding& f : lwc::analyze(source, options)) {
    check(f.span.begin <= f.span.end && f.span.end <= source.text().size());
    report.findings.push_back(lwc::locate(source, f));
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
