// lwcport's language server in a real editor: Neovim (Debian's, installed by .ci/setup), headless,
// with its built-in LSP client, driven by the scripts in tests/editor.
#include <gtest/gtest.h>

#include "support.h"

namespace lwc {
namespace {

// Runs one script of tests/editor on `file` with the cursor at (`line` 1-based, `column` 0-based
// byte); what the script reports, or the failure.
test::Run neovim(const std::string& script, const std::string& file, int line, int column, const std::string& out) {
  std::string scripts = test::source_dir() + "/tests/editor/";
  return test::run("LWCPORT_BIN=" + test::binary() + " LWCPORT_FILE=" + file + " LWCPORT_LINE=" + std::to_string(line) +
                   " LWCPORT_COLUMN=" + std::to_string(column) + " LWCPORT_OUT=" + out + " LWCPORT_SCRIPTS=" + scripts +
                   " timeout 120 nvim --headless --clean -c 'luafile " + scripts + script + "'");
}

// Neovim opens a corpus file, gets lwcport's diagnostics, applies the preferred quick fix on the
// `View.WorldCameraOrigin` finding through vim.lsp.buf.code_action, and writes the buffer: the file
// is byte for byte what `lwcport fix` writes (the file's one safe fix, on a project building
// against UE 5.4).
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
  test::Run r = neovim("quickfix.lua", dir + "/editor/HeightFogCommon.ush", 28, 56, dir + "/chosen");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_EQ(test::read(dir + "/chosen"), "use `DFSubtractDemote(.., PrimaryView.WorldCameraOrigin)`");
  EXPECT_EQ(test::read(dir + "/editor/HeightFogCommon.ush"), fixed);
}

// Neovim's hover on a use of `worldPosition` shows its kind and where it came from.
TEST(Editor, NeovimShowsAValuesKindAndProvenanceOnHover) {
  std::string dir = test::scratch("neovim-hover");
  test::write(dir + "/forward.vert", test::read(test::source_dir() + "/corpus/glsl/forward.vert"));
  test::Run r = neovim("hover.lua", dir + "/forward.vert", 18, 20, dir + "/hover");
  ASSERT_EQ(r.exit_code, 0);
  std::string shown = test::read(dir + "/hover");
  EXPECT_NE(shown.find("`worldPosition`: an absolute world position"), std::string::npos) << shown;
  EXPECT_NE(shown.find("`worldPosition` = `modelMatrix * vec4(position, 1.0)` (line 17)"), std::string::npos) << shown;
  EXPECT_NE(shown.find("`mat4 modelMatrix`, a global (line 5)"), std::string::npos) << shown;
}

}  // namespace
}  // namespace lwc
