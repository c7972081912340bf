// Bad input: each case gets a clear per-file diagnostic, the run goes on, nothing crashes.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "support.h"

namespace fs = std::filesystem;

namespace lwc {
namespace {

const std::string kGood = "float3 F(float3 L) { float3 W = mul(float4(L, 1), Primitive.LocalToWorld).xyz; return 0; }\n";

// Lints a folder holding `bad` plus a good file with one known finding, as JSON.
nlohmann::json lint_dir(const std::string& dir, const std::string& extra = "") {
  test::write(dir + "/zz_good.usf", kGood);
  auto r = test::run("cd " + dir + " && " + extra + test::binary() + " lint . --format json --fail-on none");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  auto doc = nlohmann::json::parse(r.out);
  // The run went on: the good file's finding is there.
  bool good = false;
  for (const auto& f : doc["findings"])
    if (f["path"] == "zz_good.usf" && f["rule"] == "lwc-float-world-position") good = true;
  EXPECT_TRUE(good) << doc.dump(2);
  return doc;
}

nlohmann::json finding_for(const nlohmann::json& doc, const std::string& path) {
  for (const auto& f : doc["findings"])
    if (f["path"] == path) return f;
  ADD_FAILURE() << "no finding for " << path << " in " << doc.dump(2);
  return {};
}

// The rule ids reported for one file, in report order.
std::vector<std::string> rules_for(const nlohmann::json& doc, const std::string& path) {
  std::vector<std::string> out;
  for (const auto& f : doc["findings"])
    if (f["path"] == path) out.push_back(f["rule"]);
  return out;
}

TEST(BadInput, BinaryFile) {
  std::string dir = test::scratch("binary");
  test::write(dir + "/blob.usf", std::string("float a;\n\0\x01\x02\xff", 13));
  auto f = finding_for(lint_dir(dir), "blob.usf");
  EXPECT_EQ(f["rule"], "lwc-input");
  EXPECT_EQ(f["severity"], "error");
  EXPECT_EQ(f["message"], "binary file (a NUL byte); skipped");
  EXPECT_EQ(f["start"]["line"], 2);
}

TEST(BadInput, InvalidUtf8IsReportedAndTheFileStillAnalysed) {
  std::string dir = test::scratch("utf8");
  test::write(dir + "/latin1.usf", "// caf\xe9\nfloat3 G(float3 L) { float3 W = mul(float4(L, 1), World).xyz; return 0; }\n");
  auto doc = lint_dir(dir);
  auto f = finding_for(doc, "latin1.usf");
  EXPECT_EQ(f["severity"], "warning");
  EXPECT_EQ(f["start"], (nlohmann::json{{"line", 1}, {"column", 7}}));
  EXPECT_NE(f["message"].get<std::string>().find("invalid UTF-8 (byte 0xE9)"), std::string::npos);
  auto rules = rules_for(doc, "latin1.usf");
  EXPECT_EQ(std::count(rules.begin(), rules.end(), "lwc-float-world-position"), 1);
}

TEST(BadInput, FiftyMegabyteFileIsSkippedWithBoundedMemory) {
  std::string dir = test::scratch("huge");
  std::string chunk = "float4 PadFunction(float4 X) { return X * 2.0f + float4(1, 2, 3, 4); }\n";
  std::string big;
  while (big.size() < 50u * 1024 * 1024) big += chunk;
  test::write(dir + "/huge.usf", big);
  auto f = finding_for(lint_dir(dir), "huge.usf");
  EXPECT_EQ(f["severity"], "error");
  EXPECT_NE(f["message"].get<std::string>().find("bytes, over the 16777216-byte limit; skipped"), std::string::npos);
  struct rusage usage;
  getrusage(RUSAGE_CHILDREN, &usage);
  // ru_maxrss is in KiB: the skipped file is never read, so lwcport stays far under its size.
  EXPECT_LT(usage.ru_maxrss, 200 * 1024);
  fs::remove_all(dir);  // 50 MB is too much to leave behind in /tmp
}

TEST(BadInput, CrlfLineEndingsKeepExactPositions) {
  std::string dir = test::scratch("crlf");
  test::write(dir + "/crlf.usf", "// header\r\nfloat3 F(float3 L)\r\n{\r\n\tfloat3 C = View.WorldCameraOrigin;\r\n\treturn 0;\r\n}\r\n");
  auto doc = lint_dir(dir);
  auto f = finding_for(doc, "crlf.usf");
  EXPECT_EQ(f["rule"], "lwc-float-world-position");
  EXPECT_EQ(f["start"], (nlohmann::json{{"line", 4}, {"column", 9}}));
  auto text = test::run("cd " + dir + " && " + test::binary() + " lint crlf.usf --color never").out;
  EXPECT_EQ(text.find('\r'), std::string::npos) << "source lines are shown without their CR";
}

TEST(BadInput, ByteOrderMarkIsNotAColumnOrASyntaxError) {
  std::string dir = test::scratch("bom");
  test::write(dir + "/bom.usf", "\xEF\xBB\xBF" "float3 Eye() { float3 C = View.WorldCameraOrigin; return 0; }\n");
  auto doc = lint_dir(dir);
  EXPECT_EQ(rules_for(doc, "bom.usf"), (std::vector<std::string>{"lwc-float-world-position", "lwc-primary-view"}));
  EXPECT_EQ(finding_for(doc, "bom.usf")["start"]["column"], 23);
}

TEST(BadInput, TenThousandNestedParentheses) {
  std::string dir = test::scratch("nested");
  std::string expr = std::string(10000, '(') + "View.WorldCameraOrigin" + std::string(10000, ')');
  test::write(dir + "/deep.usf", "float3 F() { float3 P = " + expr + "; return P; }\n");
  auto doc = lint_dir(dir);
  auto rules = rules_for(doc, "deep.usf");
  EXPECT_NE(std::find(rules.begin(), rules.end(), "lwc-input"), rules.end()) << "the cut analysis is reported, not hidden";
  EXPECT_EQ(finding_for(doc, "deep.usf")["start"]["line"], 1);
}

TEST(BadInput, UnterminatedComment) {
  std::string dir = test::scratch("comment");
  test::write(dir + "/open.glsl", "void main() {\n  float x = 1.0; /* never closed\n}\n");
  auto f = finding_for(lint_dir(dir), "open.glsl");
  EXPECT_EQ(f["severity"], "error");
  EXPECT_EQ(f["start"], (nlohmann::json{{"line", 2}, {"column", 18}}));
  EXPECT_EQ(f["message"], "unterminated block comment: everything after it is a comment");
}

TEST(BadInput, EmptyFile) {
  std::string dir = test::scratch("empty");
  test::write(dir + "/empty.frag", "");
  auto f = finding_for(lint_dir(dir), "empty.frag");
  EXPECT_EQ(f["severity"], "note");
  EXPECT_EQ(f["message"], "empty file; nothing to analyse");
}

TEST(BadInput, UnreadableFile) {
  std::string dir = test::scratch("unreadable");
  ::chmod(dir.c_str(), 0755);
  test::write(dir + "/secret.usf", kGood);
  ::chmod((dir + "/secret.usf").c_str(), 0);
  // Root reads anything: drop to nobody for the run so the permission check is real.
  std::string as_user = ::geteuid() == 0 ? "setpriv --reuid=65534 --regid=65534 --clear-groups " : "";
  auto f = finding_for(lint_dir(dir, as_user), "secret.usf");
  EXPECT_EQ(f["severity"], "error");
  EXPECT_EQ(f["message"], "cannot read: Permission denied");
}

TEST(BadInput, SymlinkLoopsBrokenLinksFoldersAndFifos) {
  std::string dir = test::scratch("links");
  fs::create_symlink("self.usf", dir + "/self.usf");
  fs::create_symlink("missing.usf", dir + "/broken.usf");
  fs::create_directories(dir + "/sub");
  fs::create_directory_symlink("..", dir + "/sub/up");
  fs::create_directories(dir + "/folder.hlsl");
  ASSERT_EQ(::mkfifo((dir + "/pipe.glsl").c_str(), 0644), 0);
  auto doc = lint_dir(dir);
  EXPECT_EQ(finding_for(doc, "self.usf")["message"], "cannot read: Too many levels of symbolic links");
  EXPECT_EQ(finding_for(doc, "broken.usf")["message"], "cannot read: dangling symbolic link to missing.usf: the file it points to does not exist");
  EXPECT_EQ(finding_for(doc, "sub/up")["message"], "cannot read: symlink loop: this folder is already being walked; not followed");
  EXPECT_EQ(finding_for(doc, "pipe.glsl")["message"], "cannot read: not a regular file");
  EXPECT_EQ(doc["files"], 5);  // the good file, three bad files and the loop; folder.hlsl is a folder
}

TEST(BadInput, MissingPathOnTheCommandLine) {
  // The report still says what happened; a path that yields nothing fails the run as a usage error.
  auto r = test::run(test::binary() + " lint /no/such/file.usf --format json");
  EXPECT_EQ(r.exit_code, 2);
  auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["findings"][0]["message"], "cannot read: No such file or directory");
}

}  // namespace
}  // namespace lwc
