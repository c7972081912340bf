// Every corpus shader compiles with glslang as written (plain HLSL and GLSL as they are, Unreal-era
// .usf/.ush against the Unreal environment stub of their engine era), and fixing it matches the
// fixed goldens and never introduces a compile error (fixed Unreal code against UE 5.4).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include "corpus_files.h"
#include "fix/apply.h"
#include "fix/scene.h"
#include "lang/embedded.h"
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
  if (path.rfind("corpus/ue5.0/", 0) == 0 || path.rfind("corpus/ue5.3/", 0) == 0) return 500;
  return 504;
}

// Compiles one corpus file's text against the given engine version's stub.
CompileResult compile_corpus_file(const std::string& path, const std::string& text, int version) {
  FileBuild build;
  build.lang = *lang_from_path(path);
  build.name = path;
  if (unreal_era(path)) build.unreal_version = version;
  std::string dir = fs::path(test::source_dir() + "/" + path).parent_path().string();
  build.include = [dir, lang = build.lang](const std::string& name, const std::string&) -> std::optional<IncludedFile> {
    // The library `lwcport fix` writes beside fixed files (the whole of it: fix writes a subset).
    if (name == library_file_name(lang)) return IncludedFile{name, full_library_text(lang)};
    if (name.rfind("/Engine/", 0) == 0) {
      std::string mapped = test::source_dir() + "/corpus/engine/" + name.substr(8);
      // Engine headers the corpus does not carry are what the stub declares.
      return IncludedFile{name, fs::exists(mapped) ? test::read(mapped) : std::string()};
    }
    if (fs::exists(dir + "/" + name)) return IncludedFile{name, test::read(dir + "/" + name)};
    return std::nullopt;
  };
  return compile_file(build, text);
}

// The shaders of a corpus file, each with the name it compiles under: the file, or each GLSL
// template literal of a script (a vertex stage when it writes gl_Position, else a fragment one).
std::vector<std::pair<std::string, std::string>> shaders_of(const std::string& path, const std::string& text) {
  if (!path.ends_with(".js") && !path.ends_with(".ts")) return {{path, text}};
  std::vector<std::pair<std::string, std::string>> out;
  for (Span literal : glsl_template_literals(path, text)) {
    std::string shader = text.substr(literal.begin, literal.end - literal.begin);
    out.emplace_back(path + (shader.find("gl_Position") != std::string::npos ? ".vert" : ".frag"), shader);
  }
  return out;
}

TEST(CompileCorpus, EveryShaderCompilesAsWritten) {
  for (const std::string& path : test::corpus_shaders()) {
    auto shaders = shaders_of(path, test::read(test::source_dir() + "/" + path));
    EXPECT_FALSE(shaders.empty()) << path;
    for (const auto& [name, shader] : shaders) {
      CompileResult r = compile_corpus_file(name, shader, engine_version(path));
      EXPECT_TRUE(r.ok) << format_messages(r);
    }
  }
}

// A corpus file fixed with one strategy, all fixes (safe and unsafe) applied.
FixOutcome fixed(const std::string& path, Strategy strategy) {
  Source source(path, test::read(test::source_dir() + "/" + path));
  AnalyzeOptions options;
  options.lang = *lang_from_path(path);
  options.strategy = strategy;
  // corpus/ue5.3 is a project set to UE 5.3 (its .lwcport.json); UE4 code is ported as the
  // corpus's own setting says (5.4); the rest take their era from the code.
  if (path.rfind("corpus/ue5.3/", 0) == 0) options.unreal = UnrealEra::ue5_0;
  if (path.rfind("corpus/ue4/", 0) == 0) options.unreal = UnrealEra::ue5_4;
  return fix_source(source, options, true);
}

// Lines of the functions (or top-level declarations) that still carry a finding after fixing:
// the code lwcport reported it could not port.
std::set<int> reported_lines(const std::string& path, const FixOutcome& outcome) {
  Source source(path, outcome.text);
  SyntaxTree tree = parse(source, *lang_from_path(path));
  std::set<int> lines;
  for (const Finding& f : outcome.remaining) {
    Span span = f.span;
    for (const Node& n : tree.nodes)
      if (n.depth == 1 && n.begin <= f.span.begin && f.span.end <= n.end) span = {n.begin, n.end};
    for (int l = source.position(span.begin).line; l <= source.position(span.end).line; ++l) lines.insert(l);
  }
  return lines;
}

// Golden fixed output: corpus/<dir>/<name>.fixed.<ext>, or .fixed-translated / .fixed-df where
// the strategies differ; no golden means fixing leaves the file as it is.
std::string golden_path(const std::string& path, const char* suffix) {
  fs::path p(path);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).generic_string();
}

TEST(FixCorpusGolden, FixedOutputMatchesTheGoldensAndCompiles) {
  bool update = std::getenv("LWCPORT_UPDATE_GOLDEN") != nullptr;
  for (const std::string& path : test::corpus_shaders()) {
    std::string original = test::read(test::source_dir() + "/" + path);
    FixOutcome by_translated = fixed(path, Strategy::translated), by_df = fixed(path, Strategy::df);
    const std::string &translated = by_translated.text, &df = by_df.text;
    std::map<std::string, std::string> expected;  // golden path -> text
    if (translated == df && translated != original) expected[golden_path(path, ".fixed")] = translated;
    if (translated != df) {
      if (translated != original) expected[golden_path(path, ".fixed-translated")] = translated;
      if (df != original) expected[golden_path(path, ".fixed-df")] = df;
    }
    for (const char* suffix : {".fixed", ".fixed-translated", ".fixed-df"}) {
      std::string golden = golden_path(path, suffix);
      std::string file = test::source_dir() + "/" + golden;
      if (update) {
        if (expected.count(golden)) test::write(file, expected[golden]);
        else if (fs::exists(file)) fs::remove(file);
        continue;
      }
      if (!expected.count(golden)) {
        EXPECT_FALSE(fs::exists(file)) << golden << " exists but fixing " << path << " gives another result";
        continue;
      }
      ASSERT_TRUE(fs::exists(file)) << golden << " is missing";
      EXPECT_EQ(expected[golden], test::read(file)) << golden;
    }
    // Fixed Unreal-era code is UE 5.4 code, or the era its project is set to. A fix never breaks
    // the build: where the fixed file does not compile, the error is on a line lwcport still
    // reports (a site it could not port).
    for (const FixOutcome* outcome : {&by_translated, &by_df}) {
      if (outcome->text == original) continue;
      CompileResult r = compile_corpus_file(path, outcome->text, path.rfind("corpus/ue5.3/", 0) == 0 ? 500 : 504);
      std::set<int> reported = reported_lines(path, *outcome);
      for (const CompileMessage& m : r.messages)
        EXPECT_TRUE(m.source == path && reported.count(m.line))
            << path << " after fixing: a compile error where no finding remains\n" << format_messages(r);
    }
  }
}

// The fix keeps a file's form: the same corpus file saved with a BOM and CRLF line endings fixes
// to the same text in that form, byte for byte.
TEST(FixCorpusGolden, BomAndLineEndingsAreKeptOnEveryCorpusFile) {
  auto crlf = [](const std::string& text) {
    std::string out;
    for (char c : text) out += c == '\n' ? std::string("\r\n") : std::string(1, c);
    return out;
  };
  const std::string bom = "\xEF\xBB\xBF";
  for (const std::string& path : test::corpus_shaders()) {
    std::string original = test::read(test::source_dir() + "/" + path);
    AnalyzeOptions options;
    options.lang = *lang_from_path(path);
    std::string lf = fix_source(Source(path, original), options, true).text;
    std::string windows = fix_source(Source(path, bom + crlf(original)), options, true).text;
    EXPECT_EQ(windows, bom + crlf(lf)) << path;
  }
}

}  // namespace
}  // namespace lwc
