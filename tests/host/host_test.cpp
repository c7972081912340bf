// lwcport host: the rules' examples, the host corpus and its fixes (each compiled by Clang), the
// check registry, and the command through the lwcport program.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <nlohmann/json.hpp>

#include "cli/report.h"
#include "fix/apply.h"
#include "host/check.h"
#include "host/host.h"
#include "rules/rule.h"
#include "support.h"

namespace lwc {
namespace {

namespace fs = std::filesystem;

// The corpus's headers, and Eigen's from Debian's libeigen3-dev (as compile_flags.txt says).
std::vector<std::string> include_flags() { return {"-I" + test::source_dir() + "/corpus/host/include", "-isystem", "/usr/include/eigen3"}; }
std::string include_flag() { return include_flags()[0] + " " + include_flags()[1] + " " + include_flags()[2]; }

// An example's own compile flags: a first line `// lwcport-test-flags: -ffast-math ...`.
std::vector<std::string> example_flags(const std::string& code) {
  const std::string marker = "// lwcport-test-flags:";
  std::vector<std::string> out;
  if (code.rfind(marker, 0) != 0) return out;
  std::istringstream words(code.substr(marker.size(), code.find('\n') - marker.size()));
  for (std::string w; words >> w;) out.push_back(w);
  return out;
}

// `path`: a file, or a folder whose units are analysed with its headers reported on.
HostResult analyze_file(const std::string& path, const nlohmann::json& tables = nlohmann::json::object()) {
  HostOptions options;
  options.tables = tables;
  options.paths = {path};
  options.clang_args = include_flags();
  options.clang_args.insert(options.clang_args.begin(), "-std=c++20");
  if (!fs::is_directory(path))
    for (const std::string& f : example_flags(test::read(path))) options.clang_args.push_back(f);
  return analyze_host(options);
}

const HostFile* file_named(const HostResult& r, const std::string& path) {
  for (const HostFile& f : r.files)
    if (fs::weakly_canonical(f.path) == fs::weakly_canonical(path)) return &f;
  return nullptr;
}

// Clang's verdict on a text: "" when it compiles, else its errors.
// Whether a corpus unit (or its `.fixed` twin) is Objective-C++.
bool objective_c(const std::string& path) { return path.ends_with(".mm") || path.ends_with(".mm.fixed"); }

std::string compile_errors(const std::string& path) {
  std::string language = objective_c(path) ? "objective-c++" : "c++";
  test::Run r = test::run(std::string(LWCPORT_CLANG) + " -fsyntax-only -std=c++20 -x " + language + " " + include_flag() + " " + path + " 2>&1");
  return r.exit_code == 0 ? "" : r.out.empty() ? "clang failed" : r.out;
}

std::string fixed_text(const HostFile& file, bool unsafe) {
  std::vector<Edit> edits;
  for (const Fix* fix : choose_fixes(file.findings, unsafe))
    for (const Edit& e : fix->edits)
      if (e.path.empty()) edits.push_back(e);
  return apply_edits(Source(file.path, file.text), edits);
}

// The headers beside a corpus unit (`<name>.h`): a fix may declare a member in one of them.
std::vector<fs::path> headers_beside(const fs::path& unit) {
  std::vector<fs::path> headers;
  for (const auto& e : fs::directory_iterator(unit.parent_path()))
    if (e.path().extension() == ".h") headers.push_back(e.path());
  std::sort(headers.begin(), headers.end());
  return headers;
}

std::vector<std::string> host_rules() {
  std::vector<std::string> ids;
  for (const RuleInfo& r : all_rules())
    if (r.host) ids.push_back(r.id);
  return ids;
}

class HostRuleExamples : public ::testing::TestWithParam<std::string> {};

// Bad examples are found exactly where "expect" says, good ones not at all; a "fixed" example is
// what the fix writes, it compiles, and the rule no longer fires on it.
TEST_P(HostRuleExamples, AreFoundWhereTheySayAndTheirFixesCompileClean) {
  const RuleInfo* rule = find_rule(GetParam());
  ASSERT_NE(rule, nullptr);
  std::string dir = test::scratch("host-example-" + rule->id);
  bool has_bad = false, has_good = false, has_fixed = false;
  int n = 0;
  for (const auto& ex : rule->examples) {
    ASSERT_EQ(ex.at("language"), "c++");
    bool bad = ex.contains("bad");
    std::string code = ex.at(bad ? "bad" : "good").get<std::string>();
    std::string path = dir + "/example" + std::to_string(n++) + ".cpp";
    test::write(path, code);
    ASSERT_EQ(compile_errors(path), "") << "the example itself must compile:\n" << code;
    HostResult result = analyze_file(path);
    const HostFile* file = file_named(result, path);
    std::vector<std::pair<int, int>> got, want;
    if (file)
      for (const Finding& f : file->findings) {
        EXPECT_TRUE(f.rule == rule->id || f.rule == kUnusedSuppressionRule) << f.rule << ": " << f.message;
        Position p = Source(path, file->text).position(f.span.begin);
        if (f.rule == rule->id) got.emplace_back(p.line, p.column);
      }
    if (bad)
      for (const auto& pos : ex.at("expect")) want.emplace_back(pos.at(0).get<int>(), pos.at(1).get<int>());
    EXPECT_EQ(got, want) << rule->id << (bad ? " bad" : " good") << " example:\n" << code;
    (bad ? has_bad : has_good) = true;
    if (!ex.contains("fixed")) continue;
    has_fixed = true;
    ASSERT_NE(file, nullptr);
    std::string fixed = fixed_text(*file, ex.value("unsafe", false));
    EXPECT_EQ(fixed, ex.at("fixed").get<std::string>()) << rule->id;
    test::write(path, fixed);
    EXPECT_EQ(compile_errors(path), "") << fixed;
    HostResult again = analyze_file(path);
    if (const HostFile* f = file_named(again, path))
      for (const Finding& finding : f->findings) EXPECT_NE(finding.rule, rule->id) << "still: " << finding.message;
  }
  EXPECT_TRUE(has_bad && has_good) << rule->id << " needs a bad and a good example";
  if (!rule->fixes.empty()) EXPECT_TRUE(has_fixed) << rule->id << " has fixes but no example of one";
}

INSTANTIATE_TEST_SUITE_P(HostRules, HostRuleExamples, ::testing::ValuesIn(host_rules()), [](const auto& info) {
  std::string name = info.param;
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
});

TEST(HostRegistry, EveryHostRuleHasACheckAndADocsPageAndEveryCheckItsRule) {
  for (const std::string& id : host_rules()) {
    EXPECT_EQ(host::check_factories().count(id), 1u) << id;
    EXPECT_TRUE(fs::exists(test::source_dir() + "/docs/rules/" + id + ".md")) << id;
  }
  for (const auto& [id, factory] : host::check_factories()) {
    const RuleInfo* rule = find_rule(id);
    ASSERT_NE(rule, nullptr) << id << " has no rule data";
    EXPECT_TRUE(rule->host) << id << " must say \"languages\": [\"c++\"]";
  }
}

// corpus/host/<dir>/<name>.cpp: the findings <name>.cpp.expected.json lists (LWCPORT_UPDATE_GOLDEN=1
// rewrites them; review the diff), and with every fix applied, <name>.cpp.fixed, which compiles.
// Headers beside it are the project's: a fix that edits one leaves <header>.h.fixed, and the
// fixed unit compiles against the fixed header.
TEST(HostCorpus, FindingsAndFixedFilesAreTheGoldenOnesAndCompile) {
  std::string root = test::source_dir() + "/corpus/host";
  bool update = std::getenv("LWCPORT_UPDATE_GOLDEN") != nullptr;
  // Run from outside the corpus, as from any build folder: a run reports on the folders under its
  // working directory, and the corpus's include/ stands for library headers, not the project's.
  struct Back {
    fs::path to = fs::current_path();
    ~Back() { fs::current_path(to); }
  } back;
  fs::current_path(test::scratch("host-corpus-cwd"));
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.path().extension() != ".cpp" && e.path().extension() != ".mm") continue;
    ++files;
    std::string path = e.path().string();
    ASSERT_EQ(compile_errors(path), "") << path;
    std::vector<fs::path> headers = headers_beside(e.path());
    HostOptions options;
    // compile_flags.txt beside the corpus gives the flags; a folder with headers is analysed as
    // a folder, so that its headers are reported on (and fixed) as a project's are.
    options.paths = {headers.empty() ? path : e.path().parent_path().string()};
    // A folder's .lwcport.json extends the tables, as for `lwcport host` run in that folder.
    std::string config = e.path().parent_path().string() + "/.lwcport.json";
    if (fs::exists(config)) options.tables = nlohmann::json::parse(test::read(config)).value("host", nlohmann::json::object());
    HostResult result = analyze_host(options);
    ASSERT_TRUE(result.errors.empty()) << result.errors.front();
    const HostFile* file = file_named(result, path);
    ASSERT_NE(file, nullptr) << path;
    nlohmann::json findings = nlohmann::json::array();
    Source source(path, file->text);
    std::map<std::string, Source> others;  // the headers a fix edits, by the path the run names them
    for (const HostFile& h : result.files) others.emplace(h.path, Source(h.path, h.text));
    auto other = [&](const std::string& p) -> const Source* { return others.count(p) ? &others.at(p) : nullptr; };
    for (const Finding& f : file->findings) {
      nlohmann::json j = finding_json(locate(source, f, other));
      if (j.contains("fix"))  // a header's path, as the golden keeps it: beside the unit
        for (auto& edit : j["fix"]["edits"])
          if (edit.contains("path")) edit["path"] = fs::relative(edit["path"].get<std::string>(), e.path().parent_path()).string();
      findings.push_back(j);
    }
    std::string got = nlohmann::json{{"findings", findings}}.dump(2) + "\n";
    // Every fix applied, in rounds as `lwcport host --fix` applies them (fixes that clash, as two
    // that add a member at the end of one struct, wait for the next round and its re-analysis).
    std::string scratch = test::scratch("host-corpus-fixed");
    std::string copy = scratch + "/" + e.path().filename().string();
    for (const fs::path& h : headers) test::write(scratch + "/" + h.filename().string(), test::read(h.string()));
    std::string fixed = file->text;
    size_t applied = 0, remaining = file->findings.size();
    for (int round = 0; round < 4; ++round) {
      HostResult now = round == 0 ? result : analyze_file(headers.empty() ? copy : scratch, options.tables);
      const HostFile* current = file_named(now, round == 0 ? path : copy);
      remaining = current ? current->findings.size() : 0;
      if (!current || choose_fixes(current->findings, true).empty()) break;
      applied += choose_fixes(current->findings, true).size();
      fixed = fixed_text(*current, true);
      test::write(copy, fixed);
      // The edits a fix makes in a header (named by the path the run shows, which is absolute here).
      for (const fs::path& h : headers) {
        std::string into = scratch + "/" + h.filename().string();
        const HostFile* header = file_named(now, round == 0 ? h.string() : into);
        std::vector<Edit> edits;
        for (const Fix* fix : choose_fixes(current->findings, true))
          for (const Edit& edit : fix->edits)
            if (!edit.path.empty() && fs::weakly_canonical(edit.path) == fs::weakly_canonical(round == 0 ? h : fs::path(into))) edits.push_back(edit);
        if (header && !edits.empty()) test::write(into, apply_edits(Source(header->path, header->text), edits));
      }
    }
    if (update) {
      test::write(path + ".expected.json", got);
      test::write(path + ".fixed", fixed);
      for (const fs::path& h : headers) test::write(h.string() + ".fixed", test::read(scratch + "/" + h.filename().string()));
    }
    EXPECT_EQ(got, test::read(path + ".expected.json")) << path;
    EXPECT_EQ(fixed, test::read(path + ".fixed")) << path;
    for (const fs::path& h : headers) EXPECT_EQ(test::read(scratch + "/" + h.filename().string()), test::read(h.string() + ".fixed")) << h;
    // Against the fixed headers: the copy, which includes the copies.
    test::write(copy, fixed);
    EXPECT_EQ(compile_errors(headers.empty() ? path + ".fixed" : copy), "") << path << ".fixed";
    // Each fix removed its finding and added none: what remains is what had no fix.
    EXPECT_EQ(remaining, file->findings.size() - applied) << path;
  }
  EXPECT_GE(files, 2);
}

// The high/low fixes' arithmetic, run: the golden fixed files (which the corpus test holds equal to
// what the fixes write) are compiled into a program that fills their blocks from an Earth-radius
// position, and the two halves must give the double back far closer than one float can.
TEST(HostFixes, SplitHalvesGiveTheDoubleBack) {
  const std::string corpus = test::source_dir() + "/corpus/host";
  struct Case {
    const char* language;
    std::string program;
  };
  const std::string check = R"(
static double worst_pair = 0, worst_float = 0;
static void compare(double pair, double plain, double exact) {
  worst_pair = std::fmax(worst_pair, std::fabs(pair - exact));
  worst_float = std::fmax(worst_float, std::fabs(plain - exact));
}
)";
  const std::string report = "  std::printf(\"%.17g %.17g\\n\", worst_pair, worst_float);\n  return 0;\n}\n";
  std::vector<Case> cases = {
      // glm: a model matrix split into a relative matrix and its PostTranslation.
      {"c++", "#include <cmath>\n#include <cstdio>\n#include \"" + corpus + "/opengl/ObjectBlock.cpp.fixed\"\n" + check +
                  "extern \"C\" void glBufferSubData(unsigned, long, long, const void*) {}\n"
                  "int main() {\n  SceneNode node{glm::dmat4(1.0), glm::dvec4(1.0)};\n"
                  "  node.modelMatrix[3] = glm::dvec4(6378137.123456789, -1234567.987654321, 4321098.7654321, 1.0);\n"
                  "  ObjectBlock block;\n  UploadObject(block, node);\n"
                  "  for (int i = 0; i < 3; ++i) compare(double(block.modelPostTranslation[i]) + double(block.model[3][i]), double(float(node.modelMatrix[3][i])), node.modelMatrix[3][i]);\n" +
                  report},
      // Eigen: a matrix split into a relative one and its PostTranslation.
      {"c++", "#include <cmath>\n#include <cstdio>\n#include \"" + corpus + "/eigen/ObjectUniforms.cpp.fixed\"\n" + check +
                  "Eigen::Matrix4d DepthCorrection() { return Eigen::Matrix4d::Identity(); }\n" +
                  "int main() {\n  Eigen::Vector3d p(6378137.123456789, -1234567.987654321, 4321098.7654321);\n"
                  "  Eigen::Affine3d t = Eigen::Affine3d::Identity();\n  t.translation() = p;\n"
                  "  ObjectUniforms u;\n  FillObject(u, p, t, Observer{p});\n"
                  "  for (int i = 0; i < 3; ++i) compare(double(u.modelPostTranslation[i]) + double(u.model(i, 3)), double(float(p[i])), p[i]);\n"
 +
                  report},
      // Apple's simd vectors, split with __builtin_convertvector.
      {"objective-c++", "#include <cmath>\n#include <cstdio>\n#include \"" + corpus + "/metal/FrameUniforms.mm.fixed\"\n" + check +
                            "int main() {\n  Body sun{simd_double3{6378137.123456789, -1234567.987654321, 4321098.7654321}}, eye{};\n"
                            "  FrameUniforms frame{};\n  FillFrame(frame, eye, sun, simd_double2{0.0, 0.0});\n"
                            "  for (int i = 0; i < 3; ++i) compare(double(frame.sunPosition[i]) + double(frame.sunPositionLow[i]), double(float(sun.position[i])), sun.position[i]);\n" +
                            report},
  };
  std::string dir = test::scratch("host-split-run");
  for (size_t i = 0; i < cases.size(); ++i) {
    std::string source = dir + "/case" + std::to_string(i) + ".cpp", program = dir + "/case" + std::to_string(i);
    test::write(source, cases[i].program);
    test::Run built = test::run(std::string(LWCPORT_CLANG) + " -std=c++20 -x " + cases[i].language + " " + include_flag() + " " + source +
                                " -x none -lstdc++ -lm -o " + program + " 2>&1");
    ASSERT_EQ(built.exit_code, 0) << built.out;
    test::Run ran = test::run(program);
    ASSERT_EQ(ran.exit_code, 0) << ran.out;
    double pair = 0, plain = 0;
    std::istringstream(ran.out) >> pair >> plain;
    EXPECT_LT(pair, 1e-6) << cases[i].program;  // nanometres at 6,400 km
    EXPECT_GT(plain, 1e-2) << cases[i].program;  // one float: decimetres
  }
}

// Through the lwcport program (which runs lwcport-host): every output format, the exit code, and
// a compile error reported on its file with the run going on.
TEST(HostCli, RunsThroughLwcportWithLintsOutputsAndReportsWhatClangCannotCompile) {
  std::string corpus = test::source_dir() + "/corpus/host";
  test::Run json = test::run("cd " + corpus + " && " + test::binary() + " host . --format json");
  EXPECT_EQ(json.exit_code, 1);
  nlohmann::json parsed = nlohmann::json::parse(json.out);
  size_t count = 0;
  for (const auto& finding : parsed.at("findings")) count += finding.at("rule").get<std::string>().rfind("lwc-host-", 0) == 0;
  size_t golden = 0;  // what the corpus goldens list
  for (const auto& e : fs::recursive_directory_iterator(corpus))
    if (e.path().string().ends_with(".cpp.expected.json") || e.path().string().ends_with(".mm.expected.json")) golden += nlohmann::json::parse(test::read(e.path().string())).at("findings").size();
  EXPECT_EQ(count, golden);
  EXPECT_GE(count, 20u);
  // Every message, hint and fix text filled in: no `{name}` of a template left.
  for (const auto& finding : parsed.at("findings")) {
    std::string text = finding.dump();
    for (size_t at = text.find('{', 1); at != std::string::npos; at = text.find('{', at + 1))
      EXPECT_FALSE(std::isalpha(static_cast<unsigned char>(text[at + 1])) && text.find('}', at) < text.find(' ', at)) << text;
  }
  test::Run sarif = test::run("cd " + corpus + " && " + test::binary() + " host . --format sarif");
  nlohmann::json log = nlohmann::json::parse(sarif.out);
  std::set<std::string> rules;
  for (const auto& r : log.at("runs").at(0).at("tool").at("driver").at("rules")) rules.insert(r.at("id").get<std::string>());
  EXPECT_TRUE(rules.count("lwc-host-narrowed-world-upload") && rules.count("lwc-host-narrowed-world-matrix"));
  EXPECT_EQ(log.at("runs").at(0).at("results").size(), golden);

  std::string dir = test::scratch("host-broken");
  test::write(dir + "/broken.cpp", "#include \"ue_mini.h\"\nvoid F(FParameters& P, const AActor* A)\n{\n\tP.ActorPosition = FVector3f(A->GetActorLocation());\n\tundeclared();\n}\n");
  test::Run broken = test::run("cd " + dir + " && " + test::binary() + " host broken.cpp -- -std=c++20 " + include_flag());
  EXPECT_EQ(broken.exit_code, 1);
  EXPECT_NE(broken.out.find("broken.cpp:1:1: error: Clang could not compile this translation unit: "), std::string::npos) << broken.out;
  EXPECT_NE(broken.out.find("broken.cpp:5:2: use of undeclared identifier 'undeclared'"), std::string::npos) << broken.out;
  EXPECT_NE(broken.out.find("broken.cpp:4:20: warning: `FVector3f(A->GetActorLocation())`"), std::string::npos) << broken.out;

  // A project's -Werror does not make this Clang's warnings (which its own compiler may not give) a
  // failed unit, nor does `register`, which GCC accepts in C++17 with a warning.
  test::write(dir + "/strict.cpp", "#include \"ue_mini.h\"\nvoid F(FParameters& P, const AActor* A)\n{\n\tregister int unused;\n\tP.ActorPosition = FVector3f(A->GetActorLocation());\n}\n");
  test::Run strict = test::run("cd " + dir + " && " + test::binary() + " host strict.cpp --format json -- -std=c++20 -Wall -Werror " + include_flag());
  nlohmann::json strict_findings = nlohmann::json::parse(strict.out).at("findings");
  ASSERT_EQ(strict_findings.size(), 1u) << strict.out;
  EXPECT_EQ(strict_findings[0].at("rule"), "lwc-host-narrowed-world-upload");
}

// Bad input: each problem is reported on its file with the run going on, nothing crashes.
TEST(HostCli, BadInputIsReportedOnItsFileAndTheRunGoesOn) {
  std::string dir = test::scratch("host-bad");
  test::write(dir + "/empty.cpp", "");
  test::write(dir + "/binary.cpp", std::string("\x7f" "ELF\0\0\x01\x02", 8) + std::string(64, '\0'));
  test::write(dir + "/garbage.cpp", "}}}{{{ int ( ; #include <no/such/header.h>\nvoid f() { return 1 +; }\n");
  std::string deep = "#include \"ue_mini.h\"\nvoid F(FParameters& P, const AActor* A)\n{\n\tP.Height = ";
  for (int i = 0; i < 200; ++i) deep += "(";
  deep += "A->GetActorLocation().Z";
  for (int i = 0; i < 200; ++i) deep += " + 1)";
  deep += ";\n}\n";
  test::write(dir + "/deep.cpp", deep);
  test::write(dir + "/good.cpp", "#include \"ue_mini.h\"\nvoid F(FParameters& P, const AActor* A)\n{\n\tP.ActorPosition = FVector3f(A->GetActorLocation());\n}\n");
  std::string command = "cd " + dir + " && " + test::binary() + " host . missing.cpp --format json -- -std=c++20 " + include_flag();
  test::Run r = test::run(command);
  EXPECT_EQ(r.exit_code, 2) << r.out;  // a path that does not exist fails the run, after the report
  EXPECT_NE(test::run(command + " 2>&1 >/dev/null").out.find("lwcport: error: missing.cpp: no such file or folder"), std::string::npos);
  nlohmann::json j = nlohmann::json::parse(r.out);
  std::map<std::string, std::vector<std::string>> rules;
  for (const auto& f : j.at("findings")) rules[f.at("path")].push_back(f.at("rule"));
  EXPECT_EQ(rules["garbage.cpp"], std::vector<std::string>{"lwc-input"});
  for (const auto& f : j.at("findings"))  // the first error, named by the path the user gave
    if (f.at("path") == "garbage.cpp") EXPECT_NE(f.at("message").get<std::string>().find(": garbage.cpp:1:1: "), std::string::npos) << f.dump();
  EXPECT_EQ(rules["binary.cpp"], std::vector<std::string>{"lwc-input"});
  EXPECT_EQ(rules["good.cpp"], std::vector<std::string>{"lwc-host-narrowed-world-upload"});
  EXPECT_EQ(rules.count("deep.cpp"), 0u);  // parsed, and followed only to the world model's depth: no finding, no crash
  EXPECT_EQ(rules.count("empty.cpp"), 0u);
}

// Units whose commands work in different folders, analysed side by side: each finds its own
// headers through its own relative -I (Clang works in each command's folder; the threads must not
// share one working directory).
TEST(HostCli, UnitsInDifferentFoldersFindTheirOwnHeadersOnAnyNumberOfThreads) {
  std::string dir = test::scratch("host-folders");
  for (int i = 0; i < 12; ++i) {
    std::string sub = dir + "/p" + std::to_string(i);
    test::write(sub + "/compile_flags.txt", "-std=c++20\n-Iinc\n");
    test::write(sub + "/inc/own.h", "struct Own" + std::to_string(i) + " {};\n");
    test::write(sub + "/u.cpp", "#include \"own.h\"\nOwn" + std::to_string(i) + " value;\n");
  }
  test::Run r = test::run("cd " + dir + " && " + test::binary() + " host . -j 2 --format json");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(nlohmann::json::parse(r.out).at("findings").size(), 0u) << r.out;
}

// A member judged by its name (`frame.view`) is overturned by what other units of the same run
// give it (a view from the origin, in Camera.cpp): the unit alone cannot see that, and reports it.
// On any number of threads the verdict waits for every unit.
TEST(HostRuns, AMemberNameIsOverturnedByTheValuesOtherUnitsOfTheRunGiveIt) {
  std::string folder = test::source_dir() + "/corpus/host/camera-relative";
  auto lines_of_view = [](const HostResult& r, const std::string& path) {
    std::vector<int> lines;
    const HostFile* file = file_named(r, path);
    if (!file) return lines;
    Source source(file->path, file->text);
    for (const Finding& f : file->findings)
      if (f.message.find("frame.view") != std::string::npos) lines.push_back(source.position(f.span.begin).line);
    return lines;
  };
  std::vector<int> alone = lines_of_view(analyze_file(folder + "/Draw.cpp"), folder + "/Draw.cpp");
  EXPECT_EQ(alone, (std::vector<int>{9, 10}));
  for (unsigned jobs : {1u, 2u}) {
    HostOptions options;
    options.paths = {folder};
    options.clang_args = include_flags();
    options.clang_args.insert(options.clang_args.begin(), "-std=c++20");
    options.jobs = jobs;
    HostResult together = analyze_host(options);
    EXPECT_EQ(together.units, 2u);
    EXPECT_TRUE(lines_of_view(together, folder + "/Draw.cpp").empty()) << jobs;
    // The star map's `view` is given only a matrix the tables do not know: its name still stands.
    const HostFile* draw = file_named(together, folder + "/Draw.cpp");
    ASSERT_NE(draw, nullptr);
    EXPECT_TRUE(std::any_of(draw->findings.begin(), draw->findings.end(), [](const Finding& f) { return f.message.find("stars.view") != std::string::npos; }));
  }
}

// --fix writes what --diff shows: the safe fixes, and with --unsafe-fixes the others; then reports
// what remains in the fixed files.
TEST(HostCli, FixWritesTheFixedFileAndReportsWhatRemains) {
  std::string dir = test::scratch("host-fix");
  std::string corpus = test::source_dir() + "/corpus/host/unreal/ActorParameters.cpp";
  test::write(dir + "/a.cpp", test::read(corpus));
  std::string host = "cd " + dir + " && " + test::binary() + " host a.cpp";
  std::string flags = " -- -std=c++20 " + include_flag();
  EXPECT_EQ(test::run(host + " --diff" + flags).out, "");  // every fix here is unsafe
  EXPECT_EQ(test::run(host + " --diff --unsafe-fixes" + flags).exit_code, 1);
  test::Run fixed = test::run(host + " --fix --unsafe-fixes --format json" + flags);
  EXPECT_EQ(test::read(dir + "/a.cpp"), test::read(corpus + ".fixed"));
  size_t remaining = nlohmann::json::parse(fixed.out).at("findings").size();
  EXPECT_EQ(remaining, 1u) << fixed.out;  // the one without a view in scope
  EXPECT_EQ(compile_errors(dir + "/a.cpp"), "");
}

// Two sites that would each declare the same new member: one round declares it, the next round
// splits the other site into it; the file compiles and nothing is left.
TEST(HostCli, FixSplitsEverySiteOfOneMemberInOneRun) {
  std::string dir = test::scratch("host-fix-rounds");
  std::string site = "\tP.SceneOrigin = FVector3f(A->GetActorLocation());\n";
  test::write(dir + "/a.cpp", "#include \"ue_mini.h\"\nBEGIN_SHADER_PARAMETER_STRUCT(FSceneParameters, )\n\tSHADER_PARAMETER(FVector3f, SceneOrigin)\n"
                              "END_SHADER_PARAMETER_STRUCT()\nvoid G(FSceneParameters& P, const AActor* A)\n{\n" + site +
                              "}\nvoid H(FSceneParameters& P, const AActor* A)\n{\n" + site + "}\n");
  test::Run fixed = test::run("cd " + dir + " && " + test::binary() + " host a.cpp --fix --unsafe-fixes --format json -- -std=c++20 " + include_flag() + " 2>&1");
  EXPECT_NE(fixed.out.find("Fixed 2 finding(s) in 1 file(s)."), std::string::npos) << fixed.out;
  std::string text = test::read(dir + "/a.cpp");
  auto count = [&](const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  size_t declared = count("SHADER_PARAMETER(FVector3f, SceneOriginLow)"), split = count("P.SceneOriginLow = SceneOriginDF.Low;");
  EXPECT_EQ(declared, 1u) << text;
  EXPECT_EQ(split, 2u) << text;
  EXPECT_EQ(compile_errors(dir + "/a.cpp"), "");
}

// A fix that declares its member in the project's header edits two files: --diff shows both, and
// two units that would declare the same member there clash; the second splits into the member the
// first declared, in the next round. Both units then compile against the fixed header.
TEST(HostCli, FixDeclaresTheMemberInTheProjectHeaderOnceForTwoUnits) {
  std::string dir = test::scratch("host-fix-header");
  std::string corpus = test::source_dir() + "/corpus/host/header";
  test::write(dir + "/SkyUniforms.h", test::read(corpus + "/SkyUniforms.h"));
  test::write(dir + "/a.cpp", test::read(corpus + "/SkySetup.cpp"));
  test::write(dir + "/b.cpp", "#include <glm/glm.hpp>\n\n#include \"SkyUniforms.h\"\n\nvoid Noon(SkyUniforms& sky, const glm::dvec3& sunWorldPosition)\n{\n"
                              "  sky.sunPosition = glm::vec3(sunWorldPosition);\n}\n");
  std::string host = "cd " + dir + " && " + test::binary() + " host . --unsafe-fixes";
  std::string flags = " -- -std=c++20 " + include_flag();
  test::Run diff = test::run(host + " --diff" + flags);
  EXPECT_NE(diff.out.find("+++ b/SkyUniforms.h"), std::string::npos) << diff.out;
  EXPECT_NE(diff.out.find("+  glm::vec3 sunPositionLow;"), std::string::npos) << diff.out;
  EXPECT_NE(diff.out.find("+  sky.sunPositionLow = "), std::string::npos) << diff.out;
  EXPECT_EQ(test::read(dir + "/SkyUniforms.h"), test::read(corpus + "/SkyUniforms.h"));  // --diff writes nothing
  test::Run fixed = test::run(host + " --fix --format json" + flags + " 2>&1");
  EXPECT_NE(fixed.out.find("Fixed 2 finding(s) in 3 file(s)."), std::string::npos) << fixed.out;
  std::string header = test::read(dir + "/SkyUniforms.h");
  EXPECT_EQ(header, test::read(corpus + "/SkyUniforms.h.fixed"));
  EXPECT_EQ(test::read(dir + "/a.cpp"), test::read(corpus + "/SkySetup.cpp.fixed"));
  EXPECT_NE(test::read(dir + "/b.cpp").find("sky.sunPositionLow = static_cast<glm::vec3>(sunWorldPosition - static_cast<glm::dvec3>(sky.sunPosition));"),
            std::string::npos) << test::read(dir + "/b.cpp");
  EXPECT_EQ(compile_errors(dir + "/a.cpp"), "");
  EXPECT_EQ(compile_errors(dir + "/b.cpp"), "");
}

// A suppression comment silences a host finding like a shader one; a stale one is reported.
TEST(HostCli, SuppressionsAndBaselinesWorkAsForShaders) {
  std::string dir = test::scratch("host-suppress");
  test::write(dir + "/a.cpp",
              "#include \"ue_mini.h\"\nvoid F(FParameters& P, const AActor* A)\n{\n"
              "\tP.ActorPosition = FVector3f(A->GetActorLocation());  // lwcport-ignore: lwc-host-narrowed-world-upload\n"
              "\tP.BoundsOrigin = FVector3f(A->GetActorLocation());\n"
              "\tP.Height = 1;  // lwcport-ignore: lwc-host-narrowed-world-upload\n}\n");
  std::string host = "cd " + dir + " && " + test::binary() + " host a.cpp";
  std::string flags = " -- -std=c++20 " + include_flag();
  test::Run r = test::run(host + " --format json" + flags);
  nlohmann::json j = nlohmann::json::parse(r.out);
  std::vector<std::pair<std::string, int>> got;
  for (const auto& f : j.at("findings")) got.emplace_back(f.at("rule"), f.at("start").at("line"));
  EXPECT_EQ(got, (std::vector<std::pair<std::string, int>>{{"lwc-host-narrowed-world-upload", 5}, {"lwc-unused-suppression", 6}}));
  EXPECT_EQ(test::run(host + " --write-baseline base.json" + flags).exit_code, 0);
  EXPECT_EQ(test::run(host + " --baseline base.json" + flags).exit_code, 0);
}

// report --host: the host findings as files of the era "C++ host", their effort in the total, and
// each host change that feeds a shader parameter paired with the shader files that read it.
TEST(HostReport, PairsEachHostChangeWithTheShadersThatReadItsParameter) {
  std::string dir = test::scratch("host-report");
  test::write(dir + "/Source/compile_flags.txt", "-std=c++20\n" + include_flags()[0] + "\n" + include_flags()[1] + "\n" + include_flags()[2] + "\n");
  test::write(dir + "/Source/Fill.cpp",
              "#include \"ue_mini.h\"\nvoid F(FParameters& P, const AActor* A, const FViewInfo& View)\n{\n"
              "\tP.ActorPosition = FVector3f(A->GetActorLocation());\n\tP.BoundsOrigin = FVector3f(A->GetActorLocation());\n}\n");
  // No view here: the high/low port, with the struct declared beside it.
  test::write(dir + "/Source/Scene.cpp",
              "#include \"ue_mini.h\"\nBEGIN_SHADER_PARAMETER_STRUCT(FSceneParameters, )\n\tSHADER_PARAMETER(FVector3f, SceneOrigin)\n"
              "END_SHADER_PARAMETER_STRUCT()\nvoid G(FSceneParameters& P, const AActor* A)\n{\n\tP.SceneOrigin = FVector3f(A->GetActorLocation());\n}\n");
  test::write(dir + "/Shaders/Actor.usf", "float3 ActorPosition;\nfloat3 ActorPositionScale;\nfloat4 Main(float3 P : POSITION) : SV_Position\n{\n\treturn float4(P - ActorPosition, 1);\n}\n");
  test::write(dir + "/Shaders/Other.usf", "float3 ActorPositionScale;\nfloat4 Main(float3 P : POSITION) : SV_Position\n{\n\treturn float4(P * ActorPositionScale, 1);\n}\n");
  test::Run r = test::run("cd " + dir + " && " + test::binary() + " report Shaders --host Source --out out");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  nlohmann::json j = nlohmann::json::parse(test::read(dir + "/out/report.json"));
  EXPECT_EQ(j.at("summary").at("eras").at("C++ host"), 2);
  EXPECT_EQ(j.at("host").at("findings"), 3);
  ASSERT_EQ(j.at("host").at("pairs").size(), 3u);
  EXPECT_EQ(j.at("host").at("pairs").at(0).at("where"), "Source/Fill.cpp:4");
  EXPECT_EQ(j.at("host").at("pairs").at(0).at("parameter"), "ActorPosition");
  EXPECT_EQ(j.at("host").at("pairs").at(0).at("shader_files"), nlohmann::json::array({"Shaders/Actor.usf"}));  // a whole word only
  EXPECT_EQ(j.at("host").at("pairs").at(1).at("shader_files"), nlohmann::json::array());
  EXPECT_NE(test::read(dir + "/out/report.md").find("| Source/Fill.cpp:4 | `ActorPosition` | a translated-world position | `Shaders/Actor.usf` |"),
            std::string::npos);
  EXPECT_EQ(j.at("host").at("pairs").at(2).at("port"), "high-low-position");
  EXPECT_NE(test::read(dir + "/out/report.md").find("| Source/Scene.cpp:7 | `SceneOrigin` | a high/low pair (DoubleFloat) | none found |"),
            std::string::npos);
  EXPECT_NE(test::read(dir + "/out/report.html").find("<table id=host>"), std::string::npos);
  EXPECT_NE(test::read(dir + "/out/report.html").find("a high/low pair (DoubleFloat)"), std::string::npos);
  // A host run that cannot start fails the report, which says so.
  test::Run bad = test::run("cd " + dir + " && " + test::binary() + " report Shaders --host Missing --out out2 2>&1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.out.find("Missing: no such file or folder"), std::string::npos) << bad.out;
}

}  // namespace
}  // namespace lwc
