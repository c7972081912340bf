// libFuzzer target for `lwcport host`: any bytes as a C++ translation unit (the host corpus's
// stand-in headers on its include path), parsed by Clang and walked by every host check, in this
// process so that ASan and UBSan see what would be a crash (tests/fuzz/build.sh builds it with
// them). A crash, a sanitizer report, an uncaught exception or a finding outside its file is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "host/host.h"

namespace {

void check(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace fs = std::filesystem;
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("lwcport-host-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  const fs::path unit = dir / "unit.cpp";
  std::ofstream(unit, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  lwc::HostOptions options;
  options.paths = {unit.string()};
  options.clang_args = {"-std=c++20", "-I" LWCPORT_SOURCE_DIR "/corpus/host/include", "-isystem", "/usr/include/eigen3"};
  options.isolate = false;
  lwc::HostResult result = lwc::analyze_host(options);
  check(result.units == 1 && result.counts.analysed + result.counts.failed == 1);
  for (const lwc::HostFile& file : result.files)
    for (const lwc::Finding& f : file.findings) {
      check(f.span.begin <= f.span.end && f.span.end <= file.text.size());
      for (const lwc::Fix& fix : f.fixes)
        for (const lwc::Edit& e : fix.edits) check(e.span.begin <= e.span.end);
    }
  return 0;
}
