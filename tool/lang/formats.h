#pragma once
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace lwc {

enum class Lang;

// Where a file keeps its shader code: the whole file, or GLSL in JavaScript/TypeScript template
// literals (lang/embedded.h), linted in place.
enum class Container { shader, javascript };

struct FileFormat {
  Lang lang;
  Container container;
  bool operator==(const FileFormat&) const = default;
};

// HLSL by what only HLSL writes: a `cbuffer`, a `register(..)` binding or an `SV_` semantic after
// a colon (HLSL under a GLSL extension, as Vulkan's samples name their HLSL stages .vert and .frag).
bool reads_as_hlsl(std::string_view text);

// Direct3D effect-framework blocks (.fx files of D3D9 to D3D11): a `technique`, `technique10` or
// `technique11` block, a pass's `compile vs_3_0 ...`, a `sampler_state { ... }` initialiser.
bool holds_effect_framework(std::string_view text);

// `@name` outside comments and strings: a template placeholder (neither HLSL nor GLSL has `@`)
// that an engine's own preprocessor fills in before the compiler sees the file.
bool holds_template_placeholders(std::string_view text);

// What makes a file of an extension lwcport does not map read as shader code: its language's name
// ("HLSL", "GLSL") and the words that say so (`cbuffer`, `SV_Target`). Strict, so that C++ or C#
// that mentions a `float4` is not taken for a shader; Unity's ShaderLab files (`SubShader`, a
// `CGPROGRAM` block) are not plain shader code either.
struct ShaderEvidence {
  std::string language;
  std::string words;
};
std::optional<ShaderEvidence> reads_as_shader(std::string_view text);

// Which files are shaders, by extension (the longest matching one, case-insensitive: `.glsl.js`
// before `.js`). The defaults cover what engines ship; a project's `.lwcport.json` "extensions"
// adds to them or overrides them.
class FormatTable {
 public:
  static const FormatTable& defaults();
  // ".fxh" -> "hlsl", "glsl", "glsl-in-js" or "none" (not a shader). Throws std::runtime_error
  // naming `where` for a bad extension or format.
  void set(std::string_view extension, std::string_view format, std::string_view where);
  // `text`, where known, decides the language of the stage extensions engines use for both
  // (`.vsh`, `.fsh`, `.psh`, `.csh`, `.gsh`) unless the project named it.
  std::optional<FileFormat> for_path(std::string_view path, std::string_view text = {}) const;
  // The extension (lower case, with its dot) this table maps `path` by, to a format or to none;
  // "" when it knows no extension of the name.
  std::string mapped_extension(std::string_view path) const;
  // The extensions of one language, for messages ("usf, ush, ...").
  std::string extensions() const;

 private:
  std::map<std::string, std::optional<FileFormat>> by_extension_;  // ".usf" -> format, or none
  std::map<std::string, bool> by_content_;  // extensions whose language the text decides
};

}  // namespace lwc
