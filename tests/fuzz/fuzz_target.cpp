// libFuzzer target: any bytes as a shader file (the first byte picks the extension, so every
// language and container is reached) through analyze, fix_source with unsafe fixes, and every
// output format, and the verifier's text stage (the harness kernel of the first function with a
// finding, as written and promoted to double). Built with ASan and UBSan (tests/fuzz/build.sh); a crash, an uncaught exception,
// invalid JSON output, a finding outside the file or a hang is a bug.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/report.h"
#include "fix/apply.h"
#include "rules/analyze.h"
#include "verify/kernel_builder.h"

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
