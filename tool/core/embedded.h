#pragma once
#include <string_view>
#include <vector>

namespace lwc {
struct EmbeddedFile {
  std::string_view name;
  std::string_view text;
};
// Files embedded at build time (see embed_files.cmake): every rules/*.json file, the rule pages
// (docs/rules/*.md), and the shader library sources of tool/shaderlib.
const std::vector<EmbeddedFile>& embedded_rule_files();
const std::vector<EmbeddedFile>& embedded_rule_pages();
// The bundled scene profiles (corpus/scenes/*.json), for the migration report's per-scene costs.
const std::vector<EmbeddedFile>& embedded_scene_files();
const std::vector<EmbeddedFile>& embedded_shaderlib_files();
}  // namespace lwc
