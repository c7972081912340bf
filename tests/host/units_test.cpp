// lwcport host over real builds' units: each unit in a process of its own (a crash costs that
// unit only), template code whose types are not known until instantiated, precompiled headers,
// errors this Clang raises where the project's compiler only warns, and the unit counts.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <map>
#include <thread>

#include <nlohmann/json.hpp>

#include "host/host.h"
#include "host/isolate.h"
#include "support.h"

namespace lwc {
namespace {

namespace fs = std::filesystem;

const char* const kFinding =
    "#include \"ue_mini.h\"\nvoid F(FParameters& P, const AActor* A)\n{\n\tP.ActorPosition = FVector3f(A->GetActorLocation());\n}\n";

std::string corpus_include() { return test::source_dir() + "/corpus/host/include"; }

// `lwcport host` in `dir` with `args`: its JSON, and its standard error in `err`.
nlohmann::json host_json(const std::string& dir, const std::string& args, std::string* err = nullptr) {
  test::Run r = test::run("cd " + dir + " && " + test::binary() + " host --format json " + args + " 2> " + dir + "/.stderr");
  if (err) *err = test::read(dir + "/.stderr");
  return nlohmann::json::parse(r.out);
}

std::map<std::string, std::vector<std::string>> rules_by_path(const nlohmann::json& j) {
  std::map<std::string, std::vector<std::string>> rules;
  for (const auto& f : j.at("findings")) rules[f.at("path")].push_back(f.at("rule"));
  return rules;
}

// The processes themselves: what each unit gives comes back whole (larger than a pipe holds),
// and a unit that crashes, aborts, throws or loops is reported as such while the others finish.
TEST(HostIsolation, EachUnitsOutcomeComesBackWhateverBecomesOfTheOthers) {
  std::map<size_t, std::string> done, failed;
  host::run_isolated(
      6, 3, 1,
      [](size_t i) -> std::string {
        switch (i) {
          case 1: std::raise(SIGSEGV); break;
          case 2: std::abort();
          case 3: throw std::runtime_error("no such thing");
          case 4:
            for (unsigned long n = 0;; ++n) asm volatile("" : : "r"(n));  // a loop the optimiser keeps
          default: break;
        }
        return std::string(3 << 20, static_cast<char>('a' + i));  // 3 MB: many pipe buffers
      },
      [&](size_t i, std::string&& bytes) { done[i] = std::move(bytes); },
      [&](size_t i, const std::string& why) { failed[i] = why; });
  ASSERT_EQ(done.size(), 2u);
  EXPECT_EQ(done[0], std::string(3 << 20, 'a'));
  EXPECT_EQ(done[5], std::string(3 << 20, 'f'));
  EXPECT_EQ(failed[1], "the analysis crashed (signal 11, Segmentation fault)");
  EXPECT_EQ(failed[2], "the analysis crashed (signal 6, Aborted)");
  EXPECT_EQ(failed[3], "the analysis stopped: no such thing");
  EXPECT_EQ(failed[4], "the analysis ran past 1 seconds of CPU time and was stopped");
}

// A unit on which Clang itself crashes (`#pragma clang __debug crash` traps in any build of it) is
// that unit's error; the other units' findings are reported and every unit is counted.
TEST(HostIsolation, AUnitThatCrashesCostsOnlyItsOwnFindings) {
  std::string dir = test::scratch("host-crash");
  test::write(dir + "/good.cpp", kFinding);
  test::write(dir + "/trap.cpp", "int before;\n#pragma clang __debug crash\nint after;\n");
  test::write(dir + "/also_good.cpp", kFinding);
  nlohmann::json j = host_json(dir, ". -j 2 -- -std=c++20 -I" + corpus_include());
  auto rules = rules_by_path(j);
  EXPECT_EQ(rules["good.cpp"], std::vector<std::string>{"lwc-host-narrowed-world-upload"});
  EXPECT_EQ(rules["also_good.cpp"], std::vector<std::string>{"lwc-host-narrowed-world-upload"});
  ASSERT_EQ(rules["trap.cpp"], std::vector<std::string>{"lwc-input"});
  for (const auto& f : j.at("findings"))
    if (f.at("path") == "trap.cpp")
      EXPECT_EQ(f.at("message"), "lwcport could not analyse this translation unit: the analysis crashed (signal 4, Illegal instruction); "
                                 "nothing from it is reported, the run's other units are");
  EXPECT_EQ(j.at("units"), nlohmann::json({{"analysed", 2}, {"failed", 0}, {"crashed", 1}, {"skipped", 0}}));
  // The text summary counts units apart from files (a header with findings is a file, not a unit).
  test::Run text = test::run("cd " + dir + " && " + test::binary() + " host . -- -std=c++20 -I" + corpus_include());
  EXPECT_NE(text.out.find("Translation units: 2 analysed, 0 Clang could not compile, 1 where the analysis crashed, 0 skipped (not on disk).\n"),
            std::string::npos)
      << text.out;
}

// A unit that never ends (`#pragma clang __debug overflow_stack` loops in an optimised Clang) is
// stopped at the CPU limit and reported.
TEST(HostIsolation, AUnitThatLoopsIsStoppedAtTheCpuLimit) {
  std::string dir = test::scratch("host-loop");
  test::write(dir + "/loop.cpp", "#pragma clang __debug overflow_stack\n");
  test::write(dir + "/good.cpp", kFinding);
  HostOptions options;
  options.paths = {dir};
  options.clang_args = {"-std=c++20", "-I" + corpus_include()};
  options.unit_cpu_seconds = 2;
  options.jobs = 2;
  HostResult r = analyze_host(options);
  EXPECT_EQ(r.counts.analysed, 1u);
  EXPECT_EQ(r.counts.crashed, 1u);
  bool stopped = false;
  for (const HostFile& f : r.files)
    for (const Finding& finding : f.findings)
      stopped |= f.path.ends_with("loop.cpp") &&
                 finding.message.find("ran past 2 seconds of CPU time and was stopped") != std::string::npos;
  EXPECT_TRUE(stopped);
}

// Template patterns whose expressions have dependent types or none (a parenthesised initialiser
// of a member from a dependent argument crashed lwcport-host): no crash, in one process too (as
// the fuzz target runs), and the instantiations are still read.
TEST(HostTemplates, DependentCodeIsLeftToItsInstantiations) {
  std::string dir = test::scratch("host-dependent");
  // The pattern that crashed, and Clang's other dependent shapes: a member call, `this->`, an
  // unresolved construction, a fold, a generic lambda, a dependent cast and compound assignment.
  test::write(dir + "/dependent.cpp", R"(#include "gl_mini.h"
template <typename T> struct Iter { T location; template <typename R> Iter(const R& rhs) : location(rhs.location) {} };
template <typename T> struct Pair { T worldPosition, cameraPosition;
  template <typename R> Pair(const R& a, const R& b) : worldPosition(a.worldPosition, b.x), cameraPosition{b.cameraPosition} {}
  template <typename R> void Set(const R& r) { this->worldPosition = r.Position(); cameraPosition += T(r.cameraPosition); }
};
template <typename... P> float Sum(P... p) { return (float(p) + ... + 0.0f); }
template <typename V> void Upload(GLint at, const V& worldPosition) {
  auto narrow = [](const auto& v) { return static_cast<float>(v); };
  glUniform3f(at, narrow(worldPosition.x), (float)worldPosition.y, float(worldPosition.z));
}
struct D3 { double x, y, z; };
void Use(GLint at, const D3& worldPosition) { Upload(at, worldPosition); (void)Sum(1.0, 2); }
)");
  for (bool isolate : {true, false}) {
    HostOptions options;
    options.paths = {dir + "/dependent.cpp"};
    options.clang_args = {"-std=c++20", "-I" + corpus_include()};
    options.isolate = isolate;
    HostResult r = analyze_host(options);
    EXPECT_EQ(r.counts.analysed, 1u) << isolate;
    size_t uploads = 0;
    for (const HostFile& f : r.files)
      for (const Finding& finding : f.findings) uploads += finding.rule == "lwc-host-narrowed-world-upload";
    EXPECT_EQ(uploads, 2u) << isolate;  // `(float)worldPosition.y` and `float(worldPosition.z)`, in Upload<D3>
  }
}

// CMake's precompiled headers name a file the build makes (in the format of the compiler that
// made it): the unit is read with the header it was made from, and the run says so.
TEST(HostBuilds, APrecompiledHeaderIsReadAsTheHeaderItWasMadeFrom) {
  std::string dir = test::scratch("host-pch");
  test::write(dir + "/pch/cmake_pch.hxx", "#include \"ue_mini.h\"\n");
  std::string unit = "void F(FParameters& P, const AActor* A)\n{\n\tP.ActorPosition = FVector3f(A->GetActorLocation());\n}\n";
  test::write(dir + "/a.cpp", unit);
  test::write(dir + "/b.cpp", unit);
  std::string inc = "-I" + corpus_include();
  // a.cpp as CMake writes it for Clang (the header included too); b.cpp with the PCH alone.
  nlohmann::json db = nlohmann::json::array(
      {{{"directory", dir}, {"file", dir + "/a.cpp"},
        {"command", "clang++ -std=c++20 " + inc + " -Xclang -include-pch -Xclang " + dir + "/pch/cmake_pch.hxx.pch -Xclang -include -Xclang " + dir +
                        "/pch/cmake_pch.hxx -c a.cpp"}},
       {{"directory", dir}, {"file", dir + "/b.cpp"}, {"command", "clang++ -std=c++20 " + inc + " -include-pch " + dir + "/pch/cmake_pch.hxx.pch -c b.cpp"}}});
  test::write(dir + "/compile_commands.json", db.dump());
  std::string err;
  nlohmann::json j = host_json(dir, "-p . a.cpp b.cpp", &err);
  auto rules = rules_by_path(j);
  EXPECT_EQ(rules["a.cpp"], std::vector<std::string>{"lwc-host-narrowed-world-upload"}) << j.dump();
  EXPECT_EQ(rules["b.cpp"], std::vector<std::string>{"lwc-host-narrowed-world-upload"}) << j.dump();
  EXPECT_EQ(j.at("units").at("analysed"), 2);
  EXPECT_NE(err.find("lwcport: note: the precompiled header " + dir + "/pch/cmake_pch.hxx.pch is not read: " + dir +
                     "/pch/cmake_pch.hxx, which it was made from, is included in its place"),
            std::string::npos)
      << err;
}

// What Clang 19 makes an error where GCC and older Clangs warn: an enumeration given a value
// outside its range in a constant (Boost 1.74's MPL does it), and in C an undeclared function
// and implicit int. Such units are analysed as their own compiler builds them (without the
// flags, each is that unit's lwc-input error).
TEST(HostBuilds, ErrorsOnlyThisClangRaisesDoNotFailAUnit) {
  std::string dir = test::scratch("host-clang-errors");
  test::write(dir + "/enum.cpp", std::string("enum class_kind { plain, special };\n"
                                             "constexpr class_kind none = static_cast<class_kind>(-1);\n") + kFinding);
  test::write(dir + "/old.c", "static f;\nvoid G(void)\n{\n\tundeclared();\n}\n");
  nlohmann::json db = nlohmann::json::array(
      {{{"directory", dir}, {"file", dir + "/enum.cpp"}, {"command", "clang++ -std=c++20 -I" + corpus_include() + " -c enum.cpp"}},
       {{"directory", dir}, {"file", dir + "/old.c"}, {"command", "cc -std=gnu99 -I" + corpus_include() + " -c old.c"}}});
  test::write(dir + "/compile_commands.json", db.dump());
  nlohmann::json j = host_json(dir, "-p .");
  auto rules = rules_by_path(j);
  EXPECT_EQ(rules["enum.cpp"], std::vector<std::string>{"lwc-host-narrowed-world-upload"}) << j.dump();
  EXPECT_EQ(rules.count("old.c"), 0u) << j.dump();  // no lwc-input: Clang compiled it
  EXPECT_EQ(j.at("units"), nlohmann::json({{"analysed", 2}, {"failed", 0}, {"crashed", 0}, {"skipped", 0}}));
}

// A database written with a relative `directory` ("." beside it, "../src" from a build folder):
// resolved against the database's own folder, as Clang's tools resolve it, whether named with -p
// or found upward from the unit.
TEST(HostBuilds, ARelativeDirectoryInTheDatabaseIsItsOwnFolders) {
  std::string dir = test::scratch("host-relative-dir");
  test::write(dir + "/src/a.cpp", kFinding);
  nlohmann::json here = nlohmann::json::array({{{"directory", "."}, {"file", "src/a.cpp"}, {"command", "clang++ -std=c++20 -I" + corpus_include() + " -c src/a.cpp"}}});
  test::write(dir + "/compile_commands.json", here.dump());
  EXPECT_EQ(rules_by_path(host_json(dir, "-p . src/a.cpp")), (std::map<std::string, std::vector<std::string>>{{"src/a.cpp", {"lwc-host-narrowed-world-upload"}}}));
  EXPECT_EQ(rules_by_path(host_json(dir, "src/a.cpp")), (std::map<std::string, std::vector<std::string>>{{"src/a.cpp", {"lwc-host-narrowed-world-upload"}}}));
  nlohmann::json build = nlohmann::json::array({{{"directory", "../src"}, {"file", "a.cpp"}, {"command", "clang++ -std=c++20 -I" + corpus_include() + " -c a.cpp"}}});
  test::write(dir + "/build/compile_commands.json", build.dump());
  std::string err;
  nlohmann::json j = host_json(dir, "-p build src", &err);
  EXPECT_EQ(rules_by_path(j), (std::map<std::string, std::vector<std::string>>{{"src/a.cpp", {"lwc-host-narrowed-world-upload"}}})) << j.dump() << err;
  EXPECT_EQ(err.find("not found"), std::string::npos) << err;
}

// A unit the database lists that is not on disk yet (a source the build generates) is skipped,
// counted and said, not reported as a file.
TEST(HostBuilds, AUnitNotOnDiskIsSkippedAndCounted) {
  std::string dir = test::scratch("host-generated");
  test::write(dir + "/a.cpp", kFinding);
  nlohmann::json db = nlohmann::json::array(
      {{{"directory", dir}, {"file", dir + "/a.cpp"}, {"command", "clang++ -std=c++20 -I" + corpus_include() + " -c a.cpp"}},
       {{"directory", dir}, {"file", dir + "/gen/moc_a.cpp"}, {"command", "clang++ -std=c++20 -c gen/moc_a.cpp"}}});
  test::write(dir + "/compile_commands.json", db.dump());
  std::string err;
  nlohmann::json j = host_json(dir, "-p . .", &err);
  EXPECT_EQ(rules_by_path(j), (std::map<std::string, std::vector<std::string>>{{"a.cpp", {"lwc-host-narrowed-world-upload"}}})) << j.dump();
  EXPECT_EQ(j.at("units"), nlohmann::json({{"analysed", 1}, {"failed", 0}, {"crashed", 0}, {"skipped", 1}}));
  EXPECT_NE(err.find("1 unit(s) of the compilation database are not on disk (sources the build generates?) and were skipped, first gen/moc_a.cpp"),
            std::string::npos)
      << err;
}

}  // namespace
}  // namespace lwc
