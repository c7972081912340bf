// Compiles shader files as they are, in the environment `fix --check-build` gives them (the project's
// .lwcport.json; with "engine-shaders", the engine's own headers and lwcport's stand-ins): one line
// per file, "compiles" or "fails<TAB>first error". For tests/bench/epic_port.sh, which asks which of
// Epic's own 5.x files build that way before judging lwcport's fixed 4.27 files by the same build.
#include <filesystem>
#include <iostream>

#include "project/config.h"
#include "project/files.h"
#include "project/includes.h"
#include "verify/build_environment.h"
#include "verify/compile.h"

namespace fs = std::filesystem;
using namespace lwc;

int main(int argc, char** argv) {
  ConfigFinder configs;
  IncludeSummaries includes;
  for (int i = 1; i < argc; ++i) {
    fs::path path = fs::absolute(argv[i]);
    std::shared_ptr<const ProjectConfig> config = configs.for_dir(path.parent_path());
    ReadResult text = read_file(path, config->max_file_bytes);
    if (!text.error.empty()) {
      std::cout << argv[i] << "\tunreadable\t" << text.error << "\n";
      continue;
    }
    BuildEnvironment env = build_environment(path, argv[i], text.text, Lang::hlsl, config, includes);
    FileBuild build{Lang::hlsl, argv[i], std::nullopt, false, env.include, env.defines, env.force_includes};
    CompileResult r = compile_file(build, text.text);
    std::cout << argv[i] << (r.ok ? "\tcompiles" : "\tfails");
    if (!r.ok && !r.messages.empty())
      std::cout << "\t" << r.messages.front().source << ":" << r.messages.front().line << ": " << r.messages.front().text;
    else if (!r.ok)
      std::cout << "\t" << r.crashed;
    std::cout << "\n";
  }
}
