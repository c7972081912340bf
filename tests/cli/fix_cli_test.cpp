// `lwcport fix` end to end: in-place writes that keep the file's form, refusals, --diff, and the
// guarantees over the whole corpus (idempotent; nothing a safe fix could remove is left).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/xattr.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <thread>

#include <nlohmann/json.hpp>

#include "project/files.h"
#include "support.h"

namespace fs = std::filesystem;

namespace lwc {
namespace {

const std::string kBom = "\xEF\xBB\xBF";

// A scratch project that builds against UE 5.4, where `View.WorldCameraOrigin` must move to
// PrimaryView (without the setting, UE4 code is taken as built against UE4, and that rewrite is unsafe).
std::string ue54_project(const std::string& name) {
  std::string dir = test::scratch(name);
  test::write(dir + "/.lwcport.json", "{\"unreal\": \"5.4\"}\n");
  return dir;
}

TEST(FixCli, RewritesInPlaceKeepingBomLineEndingsModeAndEverythingOutsideTheEdits) {
  std::string dir = ue54_project("fix-form");
  std::string original = kBom + "// A comment stays.\r\nfloat3 F(float3 P)\r\n{\r\n\treturn P - View.WorldCameraOrigin;  // and this\r\n}\r\n";
  test::write(dir + "/a.usf", original);
  ::chmod((dir + "/a.usf").c_str(), 0640);
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix a.usf --color never --select lwc-primary-view");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(test::read(dir + "/a.usf"),
            kBom + "// A comment stays.\r\nfloat3 F(float3 P)\r\n{\r\n\treturn DFSubtractDemote(P, PrimaryView.WorldCameraOrigin);  // and this\r\n}\r\n");
  struct stat st;
  ASSERT_EQ(::stat((dir + "/a.usf").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  // No temporary file is left behind (the project's settings and the shader only).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

// A constant buffer opened by a macro lwcport cannot see into (an engine's `META_CB_BEGIN`): the
// library's #include goes before the macro, never between it and the members.
TEST(FixCli, TheLibraryIncludeGoesBeforeAConstantBufferAMacroOpens) {
  std::string dir = test::scratch("fix-include-macro-cbuffer");
  test::write(dir + "/draw.hlsl",
              "// Per-draw constants.\n#include \"Common.hlsl\"\n\nMETA_CB_BEGIN(0, Data)\nfloat4x4 ViewProjectionMatrix;\nfloat4x4 WorldMatrix;\n"
              "META_CB_END\n\nfloat4 VS(float3 P : POSITION) : SV_Position\n{\n\tfloat3 worldPosition = mul(float4(P, 1), WorldMatrix).xyz;\n"
              "\treturn mul(float4(worldPosition, 1), ViewProjectionMatrix);\n}\n");
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix draw.hlsl --diff --unsafe-fixes --color never");
  EXPECT_NE(r.out.find("+#include \"lwc_doublefloat.hlsl\"\n META_CB_BEGIN(0, Data)\n"), std::string::npos) << r.out;
}

TEST(FixCli, ReadOnlyFileGetsAClearErrorAndTheOtherFilesAreStillFixed) {
  std::string dir = ue54_project("fix-readonly");
  std::string code = "float3 F(float3 P) { return P - View.WorldCameraOrigin; }\n";
  test::write(dir + "/a_locked.usf", code);
  test::write(dir + "/b_open.usf", code);
  ::chmod((dir + "/a_locked.usf").c_str(), 0444);
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix . --color never --select lwc-primary-view");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("a_locked.usf:1:1: error: cannot write the fixes: read-only file (mode 0444); not changed"), std::string::npos) << r.out;
  EXPECT_EQ(test::read(dir + "/a_locked.usf"), code);
  EXPECT_NE(test::read(dir + "/b_open.usf").find("PrimaryView.WorldCameraOrigin"), std::string::npos);
}

TEST(FixCli, ReplaceFileRefusesAFileThatChangedSinceItWasRead) {
  std::string dir = test::scratch("fix-changed");
  test::write(dir + "/a.usf", "edited by someone else\n");
  EXPECT_EQ(replace_file(dir + "/a.usf", "what lwcport read\n", "fixed\n"), "changed since it was read; not written (run lwcport fix again)");
  EXPECT_EQ(test::read(dir + "/a.usf"), "edited by someone else\n");
  EXPECT_EQ(replace_file(dir + "/a.usf", "edited by someone else\n", "fixed\n"), "");
  EXPECT_EQ(test::read(dir + "/a.usf"), "fixed\n");
}

// An editor saving while lwcport writes: whenever the save lands (before the read, during the
// write, after it), the user's edit survives: either the fix is refused or the edit comes after.
// Saves alternate between the two ways editors write: a new file renamed over, and in place.
TEST(FixCli, AnEditSavedWhileFixWritesIsNeverLost) {
  std::string dir = test::scratch("fix-race");
  std::string path = dir + "/a.usf";
  auto write_through = [](int fd, const std::string& text) {
    ASSERT_EQ(::ftruncate(fd, 0), 0);
    EXPECT_EQ(::pwrite(fd, text.data(), text.size(), 0), static_cast<ssize_t>(text.size()));
  };
  auto save_in_place = [&](const std::string& p, const std::string& text) {
    int fd = ::open(p.c_str(), O_WRONLY | O_TRUNC);
    if (fd >= 0) {
      write_through(fd, text);
      ::close(fd);
    }
  };
  auto save_by_rename = [](const std::string& p, const std::string& text) {
    test::write(p + ".save", text);
    ::rename((p + ".save").c_str(), p.c_str());
  };
  // An editor that opens the file, keeps it open across the fix, then saves through that descriptor.
  auto save_through_open_descriptor = [&](const std::string& p, const std::string& text, long hold) {
    int fd = ::open(p.c_str(), O_RDWR);
    if (fd < 0) return;
    std::this_thread::sleep_for(std::chrono::microseconds(hold));
    write_through(fd, text);
    ::close(fd);
  };
  // How long one replacement takes here (the fastest of 5): saves are spread over twice that.
  long fastest = 1L << 40;
  for (int i = 0; i < 5; ++i) {
    test::write(path, "original\n");
    auto start = std::chrono::steady_clock::now();
    ASSERT_EQ(replace_file(path, "original\n", "fixed\n"), "");
    fastest = std::min<long>(fastest, std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start).count());
  }
  long span = std::max<long>(50, 2 * fastest);
  std::mt19937 random(12345);
  int lost = 0, written = 0, refused = 0;
  for (int trial = 0; trial < 300; ++trial) {
    test::write(path, "original\n");
    std::string edit = "edit " + std::to_string(trial) + "\n";
    long delay = std::uniform_int_distribution<long>(0, span)(random);
    long hold = std::uniform_int_distribution<long>(0, 2 * span)(random);
    std::thread editor([&] {
      std::this_thread::sleep_for(std::chrono::microseconds(delay));
      if (trial % 3 == 0) save_in_place(path, edit);
      else if (trial % 3 == 1) save_by_rename(path, edit);
      else save_through_open_descriptor(path, edit, hold);
    });
    std::string why = replace_file(path, "original\n", "fixed\n");
    editor.join();
    (why.empty() ? written : refused) += 1;
    if (test::read(path) != edit) ++lost;
  }
  EXPECT_EQ(lost, 0) << written << " written, " << refused << " refused";
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string().find(".lwcport-"), std::string::npos) << e.path();
}

// The race a swap leaves open, made to happen every time: an editor finds the file by name before
// the fix (here an O_PATH descriptor: the lookup, without opening) and opens it for writing only
// after the fix is done. Written in place, there is one file, and the save lands in it; a new file
// swapped in would leave the save in the old one, which no one reads.
TEST(FixCli, AnEditorThatFoundTheFileBeforeTheFixSavesIntoIt) {
  std::string path = test::scratch("fix-found-before") + "/a.usf";
  test::write(path, "original\n");
  int found = ::open(path.c_str(), O_PATH);
  ASSERT_GE(found, 0);
  EXPECT_EQ(replace_file(path, "original\n", "fixed\n"), "");
  EXPECT_EQ(test::read(path), "fixed\n");
  int fd = ::open(("/proc/self/fd/" + std::to_string(found)).c_str(), O_WRONLY | O_TRUNC);
  ASSERT_GE(fd, 0);
  EXPECT_EQ(::write(fd, "edit\n", 5), 5);
  ::close(fd);
  ::close(found);
  EXPECT_EQ(test::read(path), "edit\n");
}

// A program holding the file open could write to it after the fix: such a file is left alone,
// whether it is open for writing or only for reading, and written once it is closed.
TEST(FixCli, AFileOpenInAnotherProgramIsNotChanged) {
  std::string path = test::scratch("fix-open") + "/a.usf";
  test::write(path, "original\n");
  const std::string refused = "open in another program; not changed (close it and run lwcport fix again)";
  int writer = ::open(path.c_str(), O_WRONLY);
  ASSERT_GE(writer, 0);
  EXPECT_EQ(replace_file(path, "original\n", "fixed\n"), refused);
  ASSERT_EQ(::ftruncate(writer, 0), 0);
  EXPECT_EQ(::write(writer, "edited\n", 7), 7);
  ::close(writer);
  EXPECT_EQ(test::read(path), "edited\n");
  int reader = ::open(path.c_str(), O_RDONLY);
  ASSERT_GE(reader, 0);
  EXPECT_EQ(replace_file(path, "edited\n", "fixed\n"), refused);
  ::close(reader);
  struct stat before, after;
  ASSERT_EQ(::stat(path.c_str(), &before), 0);
  EXPECT_EQ(replace_file(path, "edited\n", "fixed\n"), "");
  EXPECT_EQ(test::read(path), "fixed\n");
  // Written in place, under the lease: the same file, nothing left beside it.
  ASSERT_EQ(::stat(path.c_str(), &after), 0);
  EXPECT_EQ(after.st_ino, before.st_ino);
  for (const auto& e : fs::directory_iterator(fs::path(path).parent_path())) EXPECT_EQ(e.path().filename().string(), "a.usf");
}

// Interrupted at any moment, fix leaves no temporary file behind: each file is either the old or
// the new text, whole.
TEST(FixCli, AnInterruptedFixLeavesNoTemporaryFile) {
  std::string dir = ue54_project("fix-interrupted");
  const std::string before = "float3 F(float3 P)\n{\n\treturn P - View.WorldCameraOrigin;\n}\n";
  const std::string after = "float3 F(float3 P)\n{\n\treturn DFSubtractDemote(P, PrimaryView.WorldCameraOrigin);\n}\n";
  std::mt19937 random(7);
  for (int trial = 0; trial < 12; ++trial) {
    for (int i = 0; i < 150; ++i) test::write(dir + "/f" + std::to_string(i) + ".usf", before);
    int delay_ms = std::uniform_int_distribution<int>(5, 120)(random);
    const char* sig = trial % 2 ? "INT" : "TERM";
    test::run("cd " + dir + " && { " + test::binary() + " fix . --select lwc-primary-view --jobs 2 > /dev/null 2>&1 & pid=$!; sleep " +
              std::to_string(delay_ms / 1000.0) + "; kill -" + sig + " $pid; wait $pid; }");
    for (const auto& e : fs::directory_iterator(dir)) {
      std::string name = e.path().filename().string();
      EXPECT_EQ(name.find(".lwcport-"), std::string::npos) << "trial " << trial << ": " << name;
      if (name.ends_with(".usf")) {
        std::string text = test::read(e.path().string());
        EXPECT_TRUE(text == before || text == after) << name;
      }
    }
  }
}

TEST(FixCli, AHardLinkedFileIsNotSplitAndModeBitsAndAttributesAreKept) {
  std::string dir = test::scratch("fix-links");
  test::write(dir + "/a.usf", "read\n");
  ASSERT_EQ(::link((dir + "/a.usf").c_str(), (dir + "/b.usf").c_str()), 0);
  std::string why = replace_file(dir + "/a.usf", "read\n", "fixed\n");
  EXPECT_NE(why.find("2 hard links"), std::string::npos) << why;
  EXPECT_EQ(test::read(dir + "/b.usf"), "read\n");
  ASSERT_EQ(::unlink((dir + "/b.usf").c_str()), 0);
  ASSERT_EQ(::chmod((dir + "/a.usf").c_str(), 06754), 0);
  bool xattrs = ::setxattr((dir + "/a.usf").c_str(), "user.lwcport-test", "kept", 4, 0) == 0;  // tmpfs may refuse user.*
  EXPECT_EQ(replace_file(dir + "/a.usf", "read\n", "fixed\n"), "");
  EXPECT_EQ(test::read(dir + "/a.usf"), "fixed\n");
  struct stat st;
  ASSERT_EQ(::stat((dir + "/a.usf").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 06754u);
  if (xattrs) {
    char value[16] = {};
    EXPECT_EQ(::getxattr((dir + "/a.usf").c_str(), "user.lwcport-test", value, sizeof value), 4);
    EXPECT_STREQ(value, "kept");
  }
}

// `fix` says why a hard-linked file is left alone; --force replaces that name only.
TEST(FixCli, ForceReplacesAHardLinkedNameAndLeavesTheOthers) {
  std::string dir = ue54_project("fix-force");
  std::string code = "float3 F(float3 P) { return P - View.WorldCameraOrigin; }\n";
  test::write(dir + "/a.usf", code);
  ASSERT_EQ(::link((dir + "/a.usf").c_str(), (dir + "/b.ush").c_str()), 0);
  std::string fix = "cd " + dir + " && " + test::binary() + " fix a.usf --select lwc-primary-view --color never";
  auto refused = test::run(fix + " 2>&1");
  EXPECT_EQ(refused.exit_code, 1) << refused.out;
  EXPECT_NE(refused.out.find("a.usf:1:1: error: cannot write the fixes: it has 2 hard links"), std::string::npos) << refused.out;
  EXPECT_NE(refused.out.find("--force"), std::string::npos) << refused.out;
  EXPECT_EQ(test::read(dir + "/a.usf"), code);
  auto forced = test::run(fix + " --force 2>&1");
  EXPECT_EQ(forced.exit_code, 0) << forced.out;
  EXPECT_NE(test::read(dir + "/a.usf").find("PrimaryView."), std::string::npos);
  EXPECT_EQ(test::read(dir + "/b.ush"), code);
}

TEST(FixCli, ASymlinkStaysALinkAndItsTargetIsFixed) {
  std::string dir = ue54_project("fix-symlink");
  fs::create_directories(dir + "/real");
  test::write(dir + "/real/a.usf", "float3 F(float3 P) { return P - View.WorldCameraOrigin; }\n");
  fs::create_symlink("real/a.usf", dir + "/link.usf");
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix link.usf --select lwc-primary-view");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(fs::is_symlink(dir + "/link.usf"));
  EXPECT_NE(test::read(dir + "/real/a.usf").find("PrimaryView."), std::string::npos);
}

TEST(FixCli, DiffPrintsTheChangeAndWritesNothing) {
  std::string dir = ue54_project("fix-diff");
  std::string code = "float3 F(float3 P)\n{\n\treturn P - View.WorldCameraOrigin;\n}\n";
  test::write(dir + "/a.usf", code);
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix a.usf --diff --select lwc-primary-view");
  EXPECT_EQ(r.exit_code, 1);  // there is something to fix
  EXPECT_EQ(r.out, "--- a/a.usf\n+++ b/a.usf\n@@ -1,4 +1,4 @@\n float3 F(float3 P)\n {\n-\treturn P - View.WorldCameraOrigin;\n+\treturn DFSubtractDemote(P, PrimaryView.WorldCameraOrigin);\n }\n");
  EXPECT_EQ(test::read(dir + "/a.usf"), code);
}

// glslang's error recovery crashes on some invalid HLSL: a missing member of a uniform struct
// that holds a texture, read into a local followed by another declaration (glslang 12 as Debian
// packages it). The build check runs the compiler in a child process, so the run goes on, the
// file is reported unchecked, and the other file is still fixed.
const char* const kCrashesGlslang =
    "struct FMaterial { float3 Tint; Texture2D Albedo; SamplerState AlbedoSampler; };\n"
    "FMaterial Material;\nfloat4x4 World;\nfloat3 CameraPosition;\n"
    "float3 Tint()\n{\n\tfloat3 T = Material.Missing;\n\tfloat3 U = 1;\n\treturn U;\n}\n"
    "float3 ToCamera(float3 P)\n{\n\tfloat3 WorldPos = mul(float4(P, 1), World).xyz;\n\treturn WorldPos - CameraPosition;\n}\n";

TEST(FixCli, ACompilerCrashInTheBuildCheckCostsThatCheckOnly) {
  std::string dir = ue54_project("fix-compiler-crash");
  test::write(dir + "/a.hlsl", kCrashesGlslang);
  test::write(dir + "/b.usf", "float3 F(float3 P)\n{\n\treturn P - View.WorldCameraOrigin;\n}\n");
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix --unsafe-fixes --check-build --format json a.hlsl b.usf");
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.exit_code << r.out;
  std::string notes = nlohmann::json::parse(r.out).dump();
  EXPECT_NE(notes.find("build not checked"), std::string::npos) << notes;
  EXPECT_NE(test::read(dir + "/b.usf").find("DFSubtractDemote"), std::string::npos);
}

TEST(FixCli, ACompilerCrashCostsVerifyThatFileOnly) {
  std::string dir = test::scratch("verify-compiler-crash");
  test::write(dir + "/a.hlsl", kCrashesGlslang);
  auto r = test::run("cd " + dir + " && " + test::binary() + " verify --format json --fail-on none a.hlsl");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("ToCamera"), std::string::npos) << r.out;
}

TEST(FixCli, UnsafeFixesWaitForTheFlag) {
  std::string dir = test::scratch("fix-unsafe");
  std::string code = "float3 TileOf(FLWCVector3 P)\n{\n\treturn P.Tile;\n}\n";
  test::write(dir + "/a.usf", code);
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix a.usf --select lwc-tile-offset --color never 2>&1");
  EXPECT_NE(r.out.find("Fixed 0 finding(s) in 0 file(s). 1 more fix(es) are unsafe: rerun with --unsafe-fixes."), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("not verified"), std::string::npos) << r.out;  // nothing was rewritten
  EXPECT_EQ(test::read(dir + "/a.usf"), code);
  r = test::run("cd " + dir + " && " + test::binary() + " fix a.usf --select lwc-tile-offset --unsafe-fixes 2>&1");
  EXPECT_EQ(test::read(dir + "/a.usf"), "float3 TileOf(FDFVector3 P)\n{\n\treturn P.Tile;\n}\n");
  // Without --verify the summary says the rewrites were not measured, and how to measure them.
  EXPECT_NE(r.out.find("Fixed 1 finding(s) in 1 file(s). It was not verified on a device: `lwcport verify` measures each rewrite"),
            std::string::npos) << r.out;
}

// One fix may settle several findings (a difference of two sky members moved whole, a local moved
// to translated world with the value it is made from): the summary counts findings, not fixes.
TEST(FixCli, TheSummaryCountsTheFindingsTheFixesTookAway) {
  std::string dir = test::scratch("fix-counts-findings");
  test::write(dir + "/.lwcport.json", "{\"unreal\": \"5.4\"}");
  test::write(dir + "/a.usf",
              "float3 CameraToPlanet()\n{\n\treturn View.SkyWorldCameraOrigin - View.SkyPlanetCenterAndViewHeight.xyz;\n}\n");
  auto r = test::run("cd " + dir + " && " + test::binary() + " lint a.usf --format json --fail-on none");
  ASSERT_EQ(nlohmann::json::parse(r.out)["findings"].size(), 2u) << r.out;
  r = test::run("cd " + dir + " && " + test::binary() + " fix a.usf --color never 2>&1");
  EXPECT_NE(r.out.find("Fixed 2 finding(s) in 1 file(s)."), std::string::npos) << r.out;
  EXPECT_EQ(test::read(dir + "/a.usf"),
            "float3 CameraToPlanet()\n{\n\treturn View.SkyCameraTranslatedWorldOrigin - View.SkyPlanetTranslatedWorldCenterAndViewHeight.xyz;\n}\n");
  // A fix that writes a marker settles its finding; the marker's own finding is new, not one left.
  test::write(dir + "/b.usf", "float Far(float3 P)\n{\n\treturn length(P - ResolvedView.WorldCameraOrigin);\n}\n");
  r = test::run("cd " + dir + " && " + test::binary() + " fix b.usf --color never 2>&1");
  EXPECT_NE(r.out.find("Fixed 1 finding(s) in 1 file(s)."), std::string::npos) << r.out;
  EXPECT_NE(test::read(dir + "/b.usf").find("DFHackToFloat(ResolvedView.WorldCameraOrigin)"), std::string::npos);
}

TEST(FixCli, FixesAreLabelledInJsonAndSarif) {
  std::string code = "float3 F(float3 P) { return P - View.WorldCameraOrigin; }\n";
  // UE4 code, with no engine named: taken as built against UE4, where PrimaryView and
  // DFSubtractDemote do not exist, so the rewrite is unsafe and says why.
  std::string ue4 = test::scratch("fix-formats-ue4");
  test::write(ue4 + "/a.usf", code);
  auto inferred = nlohmann::json::parse(test::run("cd " + ue4 + " && " + test::binary() + " lint a.usf --format json --select lwc-primary-view").out);
  EXPECT_EQ(inferred["findings"][0]["fix"]["applicability"], "unsafe");
  EXPECT_EQ(inferred["findings"][0]["fix"]["reason"],
            "it needs UE 5.4+ (`DFSubtractDemote`, `PrimaryView`), and this file builds against UE4 (inferred from the code it "
            "uses; set \"unreal\" in .lwcport.json to name the engine the project builds against)");
  // The same code in a project that builds against UE 5.4: the rewrite is what makes it compile.
  std::string dir = ue54_project("fix-formats");
  test::write(dir + "/a.usf", code);
  auto json = nlohmann::json::parse(test::run("cd " + dir + " && " + test::binary() + " lint a.usf --format json --select lwc-primary-view").out);
  const auto& fix = json["findings"][0]["fix"];
  EXPECT_EQ(fix["applicability"], "safe");
  EXPECT_EQ(fix["title"], "use `DFSubtractDemote(.., PrimaryView.WorldCameraOrigin)`");
  EXPECT_EQ(fix["edits"][0], nlohmann::json::parse(R"j({"start": {"line": 1, "column": 29}, "end": {"line": 1, "column": 55}, "text": "DFSubtractDemote(P, PrimaryView.WorldCameraOrigin)"})j"));
  auto sarif = nlohmann::json::parse(test::run("cd " + dir + " && " + test::binary() + " lint a.usf --format sarif --select lwc-primary-view").out);
  const auto& result = sarif["runs"][0]["results"][0];
  const auto& replacement = result["fixes"][0]["artifactChanges"][0]["replacements"][0];
  EXPECT_EQ(replacement["deletedRegion"]["startColumn"], 29);
  EXPECT_EQ(replacement["insertedContent"]["text"], "DFSubtractDemote(P, PrimaryView.WorldCameraOrigin)");
  EXPECT_NE(result["fixes"][0]["description"]["text"].get<std::string>().find("(safe:"), std::string::npos);
}

// Plain GLSL: the High/Low rewrite includes lwcport's library, which fix writes beside the file
// with what the fixed code calls and nothing it does not.
const char* kPlainVertex =
    "#version 450\n"
    "uniform mat4 modelMatrix;\n"
    "uniform vec3 cameraPosition;\n"
    "in vec3 position;\n"
    "out float vDistance;\n"
    "void main() {\n"
    "  vec4 worldPosition = modelMatrix * vec4(position, 1.0);\n"
    "  vDistance = distance(worldPosition.xyz, cameraPosition);\n"
    "}\n";

TEST(FixCli, TheHighLowRewriteWritesTheLibraryBesideTheFixedFile) {
  std::string dir = test::scratch("fix-library");
  test::write(dir + "/a.vert", kPlainVertex);
  std::string fix = "cd " + dir + " && " + test::binary() + " fix . --unsafe-fixes --select lwc-float-world-position --color never";
  auto r = test::run(fix + " 2>&1");
  EXPECT_NE(r.out.find("Wrote lwc_doublefloat.glsl"), std::string::npos) << r.out;
  EXPECT_EQ(test::read(dir + "/a.vert"),
            "#version 450\n"
            "#extension GL_GOOGLE_include_directive : require\n"
            "#include \"lwc_doublefloat.glsl\"\n"
            "uniform FDFVector3 cameraTranslation;\n"
            "uniform mat3 modelRotationScale;\n"
            "uniform FDFVector3 modelTranslation;\n"
            "uniform vec3 cameraPosition;\n"
            "in vec3 position;\n"
            "out float vDistance;\n"
            "void main() {\n"
            "  vec4 translatedWorldPosition = vec4(modelRotationScale * position + DFFastLocalSubtractDemote(modelTranslation, cameraTranslation), 1.0);\n"
            "  vDistance = length(translatedWorldPosition.xyz);\n"
            "}\n");
  std::string library = test::read(dir + "/lwc_doublefloat.glsl");
  EXPECT_NE(library.find("vec3 DFFastLocalSubtractDemote(FDFVector3 A, FDFVector3 B)"), std::string::npos);
  EXPECT_EQ(library.find("DFMultiply"), std::string::npos) << "only what the fixed code uses";
  // Fixing again changes nothing, the library included.
  r = test::run(fix + " --diff --fail-on none");
  EXPECT_EQ(r.out, "");
  // A library file lwcport did not write is the user's: never replaced.
  test::write(dir + "/b.vert", kPlainVertex);
  test::write(dir + "/lwc_doublefloat.glsl", "// mine\n");
  r = test::run(fix + " 2>&1");
  EXPECT_NE(r.out.find("lwc_doublefloat.glsl: exists and was not written by lwcport; not changed"), std::string::npos) << r.out;
  EXPECT_EQ(test::read(dir + "/lwc_doublefloat.glsl"), "// mine\n");
  // ... and a file that would include it is not changed either: nothing includes what is missing.
  EXPECT_EQ(test::read(dir + "/b.vert"), kPlainVertex);
  EXPECT_NE(r.out.find("b.vert:1:1: error: cannot write the fixes: the library it includes could not be written"), std::string::npos) << r.out;
}

TEST(FixCli, TheHostNotesReachJsonAndSarif) {
  std::string dir = test::scratch("fix-notes");
  test::write(dir + "/a.vert", kPlainVertex);
  std::string lint = "cd " + dir + " && " + test::binary() + " lint a.vert --select lwc-float-world-position --fail-on none --format ";
  auto json = nlohmann::json::parse(test::run(lint + "json").out);
  const auto& notes = json["findings"][0]["fix"]["notes"];
  ASSERT_TRUE(notes.is_array() && notes.size() >= 2) << json.dump(2);
  EXPECT_NE(notes[0].get<std::string>().find("new uniforms: `mat3 modelRotationScale`"), std::string::npos) << notes[0];
  EXPECT_EQ(json["findings"][0]["fix"]["library"], nlohmann::json::parse(R"(["FDFVector3", "DFFastLocalSubtractDemote"])"));
  auto sarif = nlohmann::json::parse(test::run(lint + "sarif").out);
  EXPECT_EQ(sarif["runs"][0]["results"][0]["properties"]["fixNotes"], notes);
}

TEST(FixCli, DiffShowsTheLibraryAsANewFile) {
  std::string dir = test::scratch("fix-library-diff");
  test::write(dir + "/a.vert", kPlainVertex);
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix a.vert --unsafe-fixes --diff --fail-on none");
  EXPECT_NE(r.out.find("--- /dev/null\n+++ b/lwc_doublefloat.glsl\n@@ -0,0 +1,"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir + "/lwc_doublefloat.glsl"));
}

TEST(FixCli, CreateFileNeverReplaces) {
  std::string dir = test::scratch("fix-create");
  EXPECT_EQ(create_file(dir + "/new.glsl", "one\n"), "");
  EXPECT_EQ(test::read(dir + "/new.glsl"), "one\n");
  EXPECT_EQ(create_file(dir + "/new.glsl", "two\n"), "exists already; not changed");
  EXPECT_EQ(test::read(dir + "/new.glsl"), "one\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1) << "no temporary file left";
}

TEST(FixCli, FindingsTheSceneDoesNotNeedNeverFailTheRun) {
  std::string root = test::source_dir();
  auto r = test::run("cd " + root + " && " + test::binary() +
                     " lint corpus/ue4/LocalVertexFactory.ush --select lwc-float-world-position --fail-on note --color never"
                     " --explain --scene corpus/scenes/arena-2km.json");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("note: not needed in this scene:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("= scene: not needed: float32 error at the world extent 1 km is 0.00391 cm"), std::string::npos) << r.out;
  r = test::run("cd " + root + " && " + test::binary() +
                " lint corpus/ue4/LocalVertexFactory.ush --select lwc-float-world-position --fail-on note --scene corpus/scenes/planet.json");
  EXPECT_EQ(r.exit_code, 1);
}

TEST(FixCli, ABadSceneProfileIsAUsageErrorNamingTheFile) {
  std::string dir = test::scratch("fix-scene");
  test::write(dir + "/s.json", "{\"world-extent\": 5}");
  auto r = test::run("cd " + dir + " && " + test::binary() + " lint . --scene s.json 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("s.json: \"world-extent\" must be a positive distance with a unit"), std::string::npos) << r.out;
}

// The guarantees of issue 3 §5, over a copy of the whole corpus, safe and unsafe fixes applied.
TEST(FixCorpus, FixingIsIdempotentAndLeavesNothingASafeFixCouldRemove) {
  std::string dir = test::scratch("fix-corpus");
  fs::copy(test::source_dir() + "/corpus", dir + "/corpus", fs::copy_options::recursive);
  auto first = test::run("cd " + dir + " && " + test::binary() + " fix corpus --unsafe-fixes --fail-on none --format json");
  EXPECT_EQ(first.exit_code, 0);
  auto remaining = nlohmann::json::parse(first.out);  // kept: a range-for over a temporary's member dangles
  EXPECT_GT(remaining["findings"].size(), 0u);
  for (const auto& f : remaining["findings"])
    EXPECT_FALSE(f.contains("fix") && f["fix"]["applicability"] == "safe") << f.dump(2);
  auto again = test::run("cd " + dir + " && " + test::binary() + " fix corpus --unsafe-fixes --diff");
  EXPECT_EQ(again.exit_code, 0) << again.out;
  EXPECT_EQ(again.out, "");
}

}  // namespace
}  // namespace lwc
