// `lwcport report` (issue 17 part 1): the three forms agree with lint, the history counts each
// commit, and the HTML works in a real browser (Debian's Chromium, headless).
#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "support.h"

namespace lwc {
namespace {

namespace fs = std::filesystem;

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(test::read(path)); }

// Every Markdown table: a header, a separator with as many cells, rows with as many cells.
void expect_valid_tables(const std::string& markdown) {
  std::vector<std::string> lines;
  for (size_t at = 0; at <= markdown.size();) {
    size_t end = markdown.find('\n', at);
    if (end == std::string::npos) end = markdown.size();
    lines.push_back(markdown.substr(at, end - at));
    at = end + 1;
  }
  auto cells = [](const std::string& line) {
    int n = 0;
    for (size_t i = 1; i < line.size(); ++i)
      if (line[i] == '|' && line[i - 1] != '\\') ++n;
    return n;
  };
  int tables = 0;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("|", 0) != 0 || (i > 0 && lines[i - 1].rfind("|", 0) == 0)) continue;
    ++tables;
    ASSERT_LT(i + 1, lines.size());
    int width = cells(lines[i]);
    EXPECT_TRUE(std::regex_match(lines[i + 1], std::regex(R"(\|(---\|)+)"))) << lines[i + 1];
    EXPECT_EQ(cells(lines[i + 1]), width) << lines[i + 1];
    for (size_t k = i + 2; k < lines.size() && lines[k].rfind("|", 0) == 0; ++k) EXPECT_EQ(cells(lines[k]), width) << lines[k];
    EXPECT_TRUE(i == 0 || lines[i - 1].empty()) << "a table needs a blank line before it: " << lines[i - 1];
  }
  EXPECT_GE(tables, 5);
}

TEST(Report, ItsThreeFormsAgreeWithLint) {
  std::string dir = test::scratch("report");
  fs::copy(test::source_dir() + "/corpus", dir + "/corpus", fs::copy_options::recursive);
  auto run = test::run("cd " + dir + " && " + test::binary() + " report corpus --out out");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  auto lint = nlohmann::json::parse(test::run("cd " + dir + " && " + test::binary() + " lint corpus --format json --fail-on none").out);
  auto report = read_json(dir + "/out/report.json");
  EXPECT_EQ(report["version"], 1);
  EXPECT_EQ(report["summary"]["findings"], lint["findings"].size());
  EXPECT_EQ(report["summary"]["files"], lint["files"]);
  std::map<std::string, size_t> by_rule, markers;
  for (const auto& f : lint["findings"]) ++by_rule[f["rule"].get<std::string>()];
  for (const auto& row : report["summary"]["by_rule"]) EXPECT_EQ(row["findings"], by_rule[row["rule"].get<std::string>()]) << row;
  EXPECT_EQ(report["markers"].size(), by_rule["lwc-hack-marker"]);
  for (const auto& m : report["markers"]) {
    EXPECT_TRUE(std::regex_match(m["marker"].get<std::string>(), std::regex(R"(LWCHackToFloat|DF\w*_?Hack\w*|LWC_HACK_TO_ZERO)"))) << m;
    EXPECT_FALSE(m["demotes"].get<std::string>().empty()) << m;
  }
  // Safe + unsafe + by hand + not needed covers every finding; the effort states its basis.
  const auto& s = report["summary"];
  EXPECT_EQ(s["safe"].get<size_t>() + s["unsafe"].get<size_t>() + s["by_hand"].get<size_t>() + s["not_needed"].get<size_t>(), s["findings"].get<size_t>());
  EXPECT_NE(report["effort"]["basis"].get<std::string>().find("estimate"), std::string::npos);
  EXPECT_GT(report["effort"]["minutes"].get<double>(), 0);
  // Every bundled scene is priced; the small arena needs less than Unreal's full world.
  std::map<std::string, nlohmann::json> scenes;
  for (const auto& c : report["scenes"]) scenes[c["name"]] = c;
  ASSERT_EQ(scenes.size(), 4u) << report["scenes"];
  EXPECT_GT(scenes.at("2 km arena")["not_needed"].get<size_t>(), 0u);
  EXPECT_LT(scenes.at("2 km arena")["minutes"].get<double>(), scenes.at("Unreal full world (default)")["minutes"].get<double>());
  std::set<std::string> eras;
  for (const auto& f : report["files"]) eras.insert(f["era"].get<std::string>());
  EXPECT_EQ(eras, (std::set<std::string>{"GLSL", "HLSL", "UE4", "UE 5.0-5.3", "UE 5.4+"}));
  // Host-side work: every absolute uniform a shader reads is listed with what the host must upload
  // instead, and nothing is listed twice.
  std::set<std::string> uniforms, host_side;
  for (const auto& f : lint["findings"])
    if (f["rule"] == "lwc-uniform-world-float") uniforms.insert(f["path"].get<std::string>() + ":" + std::to_string(f["start"]["line"].get<int>()));
  for (const auto& h : report["host_side"]) {
    EXPECT_TRUE(host_side.insert(h["path"].get<std::string>() + ":" + std::to_string(h["line"].get<int>()) + ":" +
                                 std::to_string(h["column"].get<int>()) + h["rule"].get<std::string>()).second) << h;
    EXPECT_FALSE(h["needs"].get<std::string>().empty()) << h;
    if (h["rule"] == "lwc-uniform-world-float") uniforms.erase(h["path"].get<std::string>() + ":" + std::to_string(h["line"].get<int>()));
  }
  EXPECT_TRUE(uniforms.empty()) << *uniforms.begin();
  EXPECT_GT(report["host_side"].size(), 0u);
  // A uniform the translated port reads beside the absolute one is asked of the host once, though
  // every finding the one fix resolves carries its note.
  size_t touch = 0;
  for (const auto& h : report["host_side"])
    if (h["needs"].get<std::string>().find("`TouchTranslatedWorldPosition`") != std::string::npos) ++touch;
  EXPECT_EQ(touch, 1u);
  std::string markdown = test::read(dir + "/out/report.md");
  expect_valid_tables(markdown);
  EXPECT_NE(markdown.find("## Marker ledger (" + std::to_string(report["markers"].size()) + ")"), std::string::npos);
  EXPECT_NE(markdown.find("## Host-side work (" + std::to_string(report["host_side"].size()) + ")"), std::string::npos);
  std::string html = test::read(dir + "/out/report.html");
  EXPECT_NE(html.find("<h2>Host-side work (" + std::to_string(report["host_side"].size()) + ")</h2>"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos) << "nothing is fetched";
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find(" src="), std::string::npos);
}

// A small repository whose history changes the findings: 2, then 3, then 1.
std::string history_repo(const std::string& name) {
  std::string dir = test::scratch(name);
  std::string git = "cd " + dir + " && git -c user.name=t -c user.email=t@t ";
  const char* two = "float3 F(float3 L)\n{\n\tfloat3 W = mul(float4(L, 1), Primitive.LocalToWorld).xyz;\n\treturn W - View.WorldCameraOrigin;\n}\n";
  test::run("cd " + dir + " && git init -q");
  test::write(dir + "/s/a.usf", two);
  test::write(dir + "/s/b.usf", "float3 G(FDFVector3 P) { return DFDemote(DFAdd(P, P)); }\n");
  test::write(dir + "/s/notes.txt", "not a shader\n");
  test::run(git + "add -A && " + git + "commit -qm one");
  test::write(dir + "/s/c.usf", "float3 H(FLWCVector3 P) { return LWCHackToFloat(P); }\n");
  test::run(git + "add -A && " + git + "commit -qm two");
  test::write(dir + "/s/a.usf", "float3 F(float3 L) { return L; }\n");
  fs::remove(dir + "/s/b.usf");
  test::run(git + "add -A && " + git + "commit -qm three");
  return dir;
}

TEST(Report, HistoryCountsEveryCommitAndLintsEachFileVersionOnce) {
  std::string dir = history_repo("report-history");
  auto run = test::run("cd " + dir + " && " + test::binary() + " report s --history 5 --out out 2>&1");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  // Versions: a.usf twice, b.usf once, c.usf once.
  EXPECT_NE(run.out.find("History: 3 commit(s), 4 distinct file version(s) linted."), std::string::npos) << run.out;
  auto history = read_json(dir + "/out/report.json")["history"];
  ASSERT_EQ(history.size(), 3u);
  std::vector<std::string> subjects;
  for (const auto& h : history) subjects.push_back(h["subject"]);
  EXPECT_EQ(subjects, (std::vector<std::string>{"one", "two", "three"}));  // oldest first
  // Each commit's count is what lint says of that commit's checkout.
  for (const auto& h : history) {
    std::string checkout = dir + "/at-" + h["subject"].get<std::string>();
    test::run("cd " + dir + " && git worktree add -q " + checkout + " " + h["commit"].get<std::string>());
    auto lint = nlohmann::json::parse(test::run(test::binary() + " lint " + checkout + "/s --format json --fail-on none").out);
    EXPECT_EQ(h["findings"], lint["findings"].size()) << h;
    size_t markers = 0;
    for (const auto& f : lint["findings"]) markers += f["rule"] == "lwc-hack-marker";
    EXPECT_EQ(h["markers"], markers) << h;
  }
  EXPECT_EQ(history[2]["findings"], read_json(dir + "/out/report.json")["summary"]["findings"]);
  // --since: the commits after a revision.
  auto since = test::run("cd " + dir + " && " + test::binary() + " report s --since HEAD~2 --out out2 2>&1");
  EXPECT_NE(since.out.find("History: 2 commit(s)"), std::string::npos) << since.out;
  auto outside = test::run("cd " + test::scratch("not-a-repo") + " && " + test::binary() + " report " + dir + "/s --history 2 2>&1");
  EXPECT_EQ(outside.exit_code, 0) << outside.out;  // the repository is the one around the paths
  std::string plain = test::scratch("plain");
  test::write(plain + "/x.usf", "float F() { return 1; }\n");
  auto no_repo = test::run("cd " + plain + " && " + test::binary() + " report . --history 2 2>&1");
  EXPECT_EQ(no_repo.exit_code, 2) << no_repo.out;
  EXPECT_NE(no_repo.out.find("lwcport: error: git rev-parse"), std::string::npos) << no_repo.out;
}

// The share of a PNG's pixels that differ from its top-left pixel (the page's background).
double ink(const std::string& png) {
  EXPECT_EQ(png.substr(1, 3), "PNG");
  uint32_t width = 0, height = 0;
  int colour = 0;
  std::string idat;
  for (size_t at = 8; at + 8 <= png.size();) {
    uint32_t len = (uint8_t(png[at]) << 24) | (uint8_t(png[at + 1]) << 16) | (uint8_t(png[at + 2]) << 8) | uint8_t(png[at + 3]);
    std::string type = png.substr(at + 4, 4);
    if (type == "IHDR") {
      const char* d = png.data() + at + 8;
      width = (uint8_t(d[0]) << 24) | (uint8_t(d[1]) << 16) | (uint8_t(d[2]) << 8) | uint8_t(d[3]);
      height = (uint8_t(d[4]) << 24) | (uint8_t(d[5]) << 16) | (uint8_t(d[6]) << 8) | uint8_t(d[7]);
      EXPECT_EQ(d[8], 8) << "8-bit channels";
      colour = d[9];
    }
    if (type == "IDAT") idat += png.substr(at + 8, len);
    at += 12 + len;
  }
  int channels = colour == 6 ? 4 : colour == 2 ? 3 : 0;
  EXPECT_NE(channels, 0) << "RGB or RGBA";
  if (!channels || !width || !height) return 0;
  size_t stride = size_t(width) * channels;
  std::vector<unsigned char> raw((stride + 1) * height);
  uLongf size = raw.size();
  EXPECT_EQ(uncompress(raw.data(), &size, reinterpret_cast<const Bytef*>(idat.data()), idat.size()), Z_OK);
  std::vector<unsigned char> img(stride * height), prior(stride, 0);
  for (uint32_t y = 0; y < height; ++y) {
    unsigned char filter = raw[y * (stride + 1)];
    const unsigned char* in = &raw[y * (stride + 1) + 1];
    unsigned char* out = &img[y * stride];
    for (size_t x = 0; x < stride; ++x) {
      int a = x >= size_t(channels) ? out[x - channels] : 0, b = prior[x], c = x >= size_t(channels) ? prior[x - channels] : 0;
      int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
      int pred = filter == 1 ? a : filter == 2 ? b : filter == 3 ? (a + b) / 2 : filter == 4 ? (pa <= pb && pa <= pc ? a : pb <= pc ? b : c) : 0;
      out[x] = static_cast<unsigned char>(in[x] + pred);
    }
    std::copy(out, out + stride, prior.begin());
  }
  size_t differ = 0;
  for (size_t i = 0; i < size_t(width) * height; ++i)
    if (!std::equal(&img[i * channels], &img[i * channels] + 3, &img[0])) ++differ;
  return double(differ) / (double(width) * height);
}

std::string chromium(const std::string& args) {
  return "timeout 120 chromium --headless --no-sandbox --disable-gpu --no-first-run --disable-dev-shm-usage --window-size=1280,1600 " + args;
}

TEST(ReportBrowser, OpensInChromiumWithoutErrorsWithChartsAndAWorkingRuleFilter) {
  std::string dir = history_repo("report-browser");
  ASSERT_EQ(test::run("cd " + dir + " && " + test::binary() + " report s --history 3 --out out 2>/dev/null").exit_code, 0);
  std::string page = "file://" + dir + "/out/report.html";
  auto report = read_json(dir + "/out/report.json");
  // The page as the browser built it, with its console on standard error.
  auto dom = test::run(chromium("--enable-logging=stderr --v=0 --dump-dom '" + page + "' 2>" + dir + "/console.txt"));
  ASSERT_EQ(dom.exit_code, 0);
  std::string console = test::read(dir + "/console.txt");
  EXPECT_EQ(console.find(":CONSOLE"), std::string::npos) << "the page logged or threw:\n" << console;
  EXPECT_NE(dom.out.find("<svg id=\"rule-chart\""), std::string::npos);
  EXPECT_NE(dom.out.find("<svg id=\"burn-down\""), std::string::npos);
  EXPECT_NE(dom.out.find("<polyline class=\"total\""), std::string::npos);
  auto visible = [&](const std::string& html) {
    std::string table = html.substr(html.find("<table id=\"findings\""));
    table = table.substr(0, table.find("</table>"));
    size_t rows = 0, hidden = 0;
    for (size_t at = 0; (at = table.find("<tr data-rules=", at)) != std::string::npos; ++at) {
      ++rows;
      hidden += table.substr(at, table.find('>', at) - at).find("hidden") != std::string::npos;
    }
    return rows - hidden;
  };
  EXPECT_EQ(visible(dom.out), report["findings"].size());
  // The filter, chosen as a link would choose it: only that rule's rows stay.
  auto filtered = test::run(chromium("--dump-dom '" + page + "#rule=lwc-hack-marker' 2>/dev/null"));
  size_t markers = 0;
  for (const auto& f : report["findings"]) markers += f["rule"] == "lwc-hack-marker";
  ASSERT_GT(markers, 0u);
  EXPECT_LT(markers, report["findings"].size());
  EXPECT_EQ(visible(filtered.out), markers);
  EXPECT_NE(filtered.out.find("id=\"shown\">" + std::to_string(markers) + "<"), std::string::npos);
  // The screenshot shows a page, not a blank one: some of it differs from the background.
  test::run(chromium("--screenshot=" + dir + "/shot.png '" + page + "' > /dev/null 2>&1"));
  double drawn = ink(test::read(dir + "/shot.png"));
  EXPECT_GT(drawn, 0.02) << "share of the screenshot that is not background";
  test::write(dir + "/blank.html", "<!DOCTYPE html><html><body></body></html>");
  test::run(chromium("--screenshot=" + dir + "/blank.png 'file://" + dir + "/blank.html' > /dev/null 2>&1"));
  EXPECT_LT(ink(test::read(dir + "/blank.png")), 0.001) << "the measure itself: a blank page has no ink";
}

TEST(Report, VerifyAddsEachFunctionsErrorAgainstCostPlot) {
  std::string dir = test::scratch("report-verify");
  fs::copy(test::source_dir() + "/corpus", dir + "/corpus", fs::copy_options::recursive);
  auto run = test::run("cd " + dir + " && " + test::binary() + " report corpus/ue5.4/DistanceFieldShadowDF.usf --verify --out out 2>&1");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  auto report = read_json(dir + "/out/report.json");
  ASSERT_TRUE(report["verification"].is_array()) << report["verification"];
  ASSERT_GE(report["verification"].size(), 2u);
  std::string html = test::read(dir + "/out/report.html");
  size_t plots = 0, fronts = 0;
  for (size_t at = 0; (at = html.find("<svg class=verify", at)) != std::string::npos; ++at) ++plots;
  for (size_t at = 0; (at = html.find("<polyline class=front", at)) != std::string::npos; ++at) ++fronts;
  EXPECT_EQ(plots, report["verification"].size());
  size_t with_front = 0;  // functions where some variant passes: the front joins those
  for (const auto& fn : report["verification"])
    with_front += std::any_of(fn["variants"].begin(), fn["variants"].end(), [](const auto& v) { return v["paretoFront"] == true; });
  EXPECT_GT(with_front, 0u);
  EXPECT_EQ(fronts, with_front);
  EXPECT_NE(test::read(dir + "/out/report.md").find("## Verification"), std::string::npos);
}

}  // namespace
}  // namespace lwc
