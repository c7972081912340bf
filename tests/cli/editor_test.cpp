// lwcport's language server in a real editor: Neovim (Debian's 0.7.2, installed by .ci/setup),
// headless, with its built-in LSP client, set up as docs/editors.md shows and driven by the
// scripts in tests/editor.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>

#include "support.h"

namespace lwc {
namespace {

// The `n`th Lua block (0-based) under "## Neovim" in docs/editors.md, or "" (a failure).
std::string documented_lua(int n) {
  std::string page = test::read(test::source_dir() + "/docs/editors.md");
  size_t begin = page.find("\n## Neovim\n"), end = begin;
  for (int i = 0; i <= n && begin != std::string::npos; ++i) {
    begin = page.find("```lua\n", end);
    end = begin == std::string::npos ? begin : page.find("\n```\n", begin);
    begin = end == std::string::npos ? end : begin + 7;
  }
  if (begin == std::string::npos) {
    ADD_FAILURE() << "docs/editors.md shows no Lua block " << n << " under \"## Neovim\"";
    return "";
  }
  return page.substr(begin, end + 1 - begin);
}

// The Neovim set-up docs/editors.md shows for 0.7 (its first Lua block), written to
// `dir`/init.lua: Neovim runs with it as a user's init.lua, so the page and the tests cannot drift
// apart.
std::string documented_init(const std::string& dir) {
  test::write(dir + "/init.lua", documented_lua(0));
  return dir + "/init.lua";
}

// Every shader extension lwcport reads (README), with the Neovim file type it should open as.
std::map<std::string, std::string> shader_filetypes() {
  std::map<std::string, std::string> filetypes;
  for (const char* e : {"usf", "ush", "hlsl", "hlsli", "fx", "fxh", "cginc"}) filetypes[e] = "hlsl";
  for (const char* e : {"glsl", "vert", "frag", "comp", "geom", "tesc", "tese", "mesh", "task", "rgen", "rchit", "rmiss", "rahit",
                        "rint", "rcall", "vsh", "fsh", "sc"})
    filetypes[e] = "glsl";
  return filetypes;
}

// Runs one script of tests/editor in Neovim started as a user starts it (no user files, the
// documented set-up as init.lua, lwcport first on PATH), with `vars` (`LWCPORT_X=...` words) in
// its environment; what Neovim printed and its exit code (2 when the script stopped on an error).
test::Run neovim(const std::string& script, const std::string& dir, const std::string& vars) {
  std::string init = documented_init(dir);
  std::string scripts = test::source_dir() + "/tests/editor/";
  std::string bin = std::filesystem::path(test::binary()).parent_path().string();
  return test::run("PATH=" + bin + ":$PATH LWCPORT_SCRIPTS=" + scripts + " " + vars + " timeout 120 nvim --headless --clean -u " + init +
                   " -c 'luafile " + scripts + script + "' -c 'cquit 2'");
}

// `file` open with the cursor at (`line` 1-based, `column` 0-based byte).
std::string at(const std::string& file, int line, int column) {
  return "LWCPORT_FILE=" + file + " LWCPORT_LINE=" + std::to_string(line) + " LWCPORT_COLUMN=" + std::to_string(column);
}

// Neovim opens a corpus file, gets lwcport's diagnostics, applies the preferred quick fix on the
// `View.WorldCameraOrigin` finding through vim.lsp.buf.code_action, and writes the buffer: that
// line is byte for byte what `lwcport fix` writes there (on a project building against UE 5.4),
// and every other line is as it was (the quick fix is one finding's, `fix` takes them all).
TEST(Editor, NeovimAppliesAQuickFixAsLwcportFixDoes) {
  std::string dir = test::scratch("neovim-quickfix");
  std::string text = test::read(test::source_dir() + "/corpus/ue4/HeightFogCommon.ush");
  for (const char* where : {"/editor", "/cli"}) {
    test::write(dir + where + "/HeightFogCommon.ush", text);
    test::write(dir + where + "/.lwcport.json", R"({"unreal": "5.4"})");
  }
  test::run(test::binary() + " fix " + dir + "/cli/HeightFogCommon.ush --fail-on none > /dev/null");
  std::string fixed = test::read(dir + "/cli/HeightFogCommon.ush");
  ASSERT_NE(fixed, text);
  test::Run r = neovim("quickfix.lua", dir, at(dir + "/editor/HeightFogCommon.ush", 28, 56) + " LWCPORT_OUT=" + dir + "/chosen");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(test::read(dir + "/chosen"), "use `DFSubtractDemote(.., PrimaryView.WorldCameraOrigin)`");
  auto lines = [](const std::string& t) {
    std::vector<std::string> out;
    std::stringstream in(t);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
  };
  std::vector<std::string> expected = lines(text), by_fix = lines(fixed);
  ASSERT_EQ(expected.size(), by_fix.size());
  ASSERT_NE(expected[27], by_fix[27]);
  expected[27] = by_fix[27];
  EXPECT_EQ(lines(test::read(dir + "/editor/HeightFogCommon.ush")), expected);
}

// Neovim's hover on a use of `worldPosition` shows its kind and where it came from.
TEST(Editor, NeovimShowsAValuesKindAndProvenanceOnHover) {
  std::string dir = test::scratch("neovim-hover");
  test::write(dir + "/forward.vert", test::read(test::source_dir() + "/corpus/glsl/forward.vert"));
  test::Run r = neovim("hover.lua", dir, at(dir + "/forward.vert", 18, 20) + " LWCPORT_OUT=" + dir + "/hover");
  ASSERT_EQ(r.exit_code, 0);
  std::string shown = test::read(dir + "/hover");
  EXPECT_NE(shown.find("`worldPosition`: an absolute world position"), std::string::npos) << shown;
  EXPECT_NE(shown.find("`worldPosition` = `modelMatrix * vec4(position, 1.0)` (line 17)"), std::string::npos) << shown;
  EXPECT_NE(shown.find("`mat4 modelMatrix`, a global (line 5)"), std::string::npos) << shown;
}

// A file of each shader extension lwcport reads (README) opens in Neovim with the file type of
// its language, is served by lwcport and gets its diagnostics. Each starts with a `#` line, as
// real shaders do (`#include`, `#version`), which Neovim's own detection takes for `conf`.
TEST(Editor, NeovimServesEveryShaderExtension) {
  std::string dir = test::scratch("neovim-filetypes");
  std::string hlsl = test::read(test::source_dir() + "/corpus/ue4/HeightFogCommon.ush");
  std::string glsl = test::read(test::source_dir() + "/corpus/glsl/forward.vert");
  std::map<std::string, std::string> expected;
  std::string files;
  for (const auto& [extension, lang] : shader_filetypes()) {
    expected["shader." + extension] = lang;
    test::write(dir + "/project/shader." + extension, lang == "hlsl" ? hlsl : glsl);
    files += dir + "/project/shader." + extension + " ";
  }
  test::Run r = neovim("filetypes.lua", dir, "LWCPORT_FILES='" + files + "' LWCPORT_OUT=" + dir + "/served");
  ASSERT_EQ(r.exit_code, 0);
  std::istringstream served(test::read(dir + "/served"));
  std::map<std::string, std::string> seen;
  std::string name, filetype, server;
  int diagnostics;
  while (served >> name >> filetype >> server >> diagnostics) {
    seen[name] = filetype;
    EXPECT_EQ(server, "lwcport") << name;
    EXPECT_GT(diagnostics, 0) << name;
  }
  EXPECT_EQ(seen, expected);
}

// Files of one project (found by its .lwcport.json, here from a subfolder) share one client and
// one server process; a file of another project (found by its .git, a worktree's file) gets its
// own. Two processes in all, not one a file.
TEST(Editor, NeovimRunsOneServerPerProject) {
  std::string dir = test::scratch("neovim-servers");
  std::string hlsl = test::read(test::source_dir() + "/corpus/ue4/HeightFogCommon.ush");
  test::write(dir + "/one/.lwcport.json", "{}");
  test::write(dir + "/one/Fog.usf", hlsl);
  test::write(dir + "/one/Private/Fog.ush", hlsl);
  test::write(dir + "/two/.git", "gitdir: /elsewhere/.git/worktrees/two\n");
  test::write(dir + "/two/shaders/forward.vert", test::read(test::source_dir() + "/corpus/glsl/forward.vert"));
  std::string files = dir + "/one/Fog.usf " + dir + "/one/Private/Fog.ush " + dir + "/two/shaders/forward.vert";
  test::Run r = neovim("servers.lua", dir, "LWCPORT_FILES='" + files + "' LWCPORT_OUT=" + dir + "/servers");
  ASSERT_EQ(r.exit_code, 0);
  std::istringstream out(test::read(dir + "/servers"));
  std::string name[3];
  int client[3], pid[3], clients, processes;
  std::string word;
  for (int i = 0; i < 3; ++i) out >> name[i] >> client[i] >> pid[i];
  out >> word >> clients >> word >> processes;
  ASSERT_TRUE(out) << test::read(dir + "/servers");
  EXPECT_EQ(client[0], client[1]);
  EXPECT_EQ(pid[0], pid[1]);
  EXPECT_NE(client[0], client[2]);
  EXPECT_NE(pid[0], pid[2]);
  EXPECT_EQ(clients, 2);
  EXPECT_EQ(processes, 2);
}

// An include edited in Neovim and not saved is what its includer is analysed with: making the
// include's camera position translated (the origin) takes the includer's finding away, undoing the
// edit brings it back, and nothing is written.
TEST(Editor, NeovimReanalysesAnIncluderWhenItsIncludeIsEditedUnsaved) {
  std::string dir = test::scratch("neovim-include");
  std::string include =
      "// Where the sun's disc is drawn: a point far along the light's direction, seen from the camera.\n"
      "float3 SunDiscPosition(float3 LightDirection)\n"
      "{\n"
      "\tfloat3 Eye = ResolvedView.WorldCameraOrigin;\n"
      "\treturn Eye + LightDirection * 1e6;\n"
      "}\n";
  test::write(dir + "/project/.lwcport.json", "{}");
  test::write(dir + "/project/Sky.ush", include);
  test::write(dir + "/project/SkyPass.usf",
              "#include \"Sky.ush\"\n"
              "\n"
              "float SunGlow(float3 LightDirection, float3 PixelPosition)\n"
              "{\n"
              "\tfloat3 Sun = SunDiscPosition(LightDirection);\n"
              "\treturn 1.0 / (1.0 + length(Sun - PixelPosition));\n"
              "}\n");
  test::write(dir + "/edit", "\tfloat3 Eye = float3(0, 0, 0);  // translated world: the camera is the origin\n");
  std::string files = dir + "/project/SkyPass.usf " + dir + "/project/Sky.ush";
  test::Run r = neovim("include.lua", dir,
                       "LWCPORT_FILES='" + files + "' LWCPORT_LINE=4 LWCPORT_EDIT=" + dir + "/edit LWCPORT_OUT=" + dir + "/steps");
  ASSERT_EQ(r.exit_code, 0);
  // The includer's diagnostics: opened, after the edit, whether the include was unsaved then, after the undo.
  EXPECT_EQ(test::read(dir + "/steps"), "lwc-float-world-position@5\n\ntrue\nlwc-float-world-position@5\n");
  EXPECT_EQ(test::read(dir + "/project/Sky.ush"), include);
}

// The set-up docs/editors.md shows for Neovim 0.10 cannot run here (Debian 12 has 0.7.2): it is
// Lua that loads, and its vim.filetype.add table gives every shader extension its file type.
TEST(Editor, TheNeovim010SetUpLoadsAndNamesEveryExtension) {
  std::string dir = test::scratch("neovim-010");
  std::string lua = documented_lua(1);
  test::write(dir + "/init.lua", lua);
  test::Run r = test::run("nvim --headless --clean -c \"lua local ok, e = loadfile('" + dir +
                          "/init.lua') if not ok then io.stderr:write(e) vim.cmd('cquit 1') end\" -c 'qall!'");
  EXPECT_EQ(r.exit_code, 0);
  for (const auto& [extension, lang] : shader_filetypes())
    EXPECT_NE(lua.find(" " + extension + " = \"" + lang + "\","), std::string::npos) << extension;
}

}  // namespace
}  // namespace lwc
