// Every corpus shader compiles with glslang before and after `lwcport fix`: plain HLSL and GLSL
// as they are, Unreal-era files (.usf/.ush) against the Unreal environment stub, fixed plain files
// with the DoubleFloat library that fix writes beside them.
#include <gtest/gtest.h>

#include <filesystem>

#include "corpus_files.h"
#include "fix/apply.h"
#include "shaderlib/shaderlib.h"
#include "support.h"
#include "verify/compile.h"

namespace fs = std::filesystem;

namespace lwc {
namespace {

bool unreal_era(const std::string& path) { return path.ends_with(".usf") || path.ends_with(".ush"); }

// The engine version a corpus file was written for (LWCPORT_UE_VERSION of the stub).
int engine_version(const std::string& path) {
  if (path.rfind("corpus/ue4/", 0) == 0) return 427;
  if (path.rfind("corpus/ue5.0/", 0) == 0) return 500;
  return 504;
}

// Compiles one corpus file's text; `beside` maps names of files next to it (the library) to text.
CompileResult compile_corpus_file(const std::string& path, const std::string& text, int version,
                                  const std::map<std::string, std::string>& beside = {}) {
  CompileInput in;
  in.lang = *lang_from_path(path);
  in.name = path;
  in.text = text;
  if (in.lang == Lang::hlsl) {
    // Fragments and files with their own entry points alike: check every function through a
    // do-nothing entry point appended after the file (line numbers unchanged).
    in.stage = Stage::fragment;
    in.entry = "lwcport_compile_check";
    in.text += "\nvoid lwcport_compile_check() {}\n";
    if (unreal_era(path))
      in.preamble = "#define LWCPORT_UE_VERSION " + std::to_string(version) + "\n" + unreal_environment_text();
  } else {
    in.stage = stage_from_extension(path).value_or(Stage::fragment);
  }
  std::string dir = fs::path(test::source_dir() + "/" + path).parent_path().string();
  in.include = [&, dir](const std::string& name, const std::string&) -> std::optional<std::string> {
    if (auto it = beside.find(name); it != beside.end()) return it->second;
    if (name.rfind("/Engine/", 0) == 0) {
      std::string mapped = test::source_dir() + "/corpus/engine/" + name.substr(8);
      // Engine headers the corpus does not carry are what the stub declares.
      return fs::exists(mapped) ? test::read(mapped) : std::string();
    }
    if (fs::exists(dir + "/" + name)) return test::read(dir + "/" + name);
    return std::nullopt;
  };
  return compile_shader(in);
}

std::string messages(const CompileResult& r) {
  std::string out;
  for (const CompileMessage& m : r.messages) out += m.source + ":" + std::to_string(m.line) + ": " + m.text + "\n";
  return out;
}

TEST(CompileCorpus, EveryShaderCompilesAsWritten) {
  for (const std::string& path : test::corpus_shaders()) {
    CompileResult r = compile_corpus_file(path, test::read(test::source_dir() + "/" + path), engine_version(path));
    EXPECT_TRUE(r.ok) << messages(r);
  }
}

}  // namespace
}  // namespace lwc
