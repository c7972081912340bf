#include "lang/formats.h"

#include <algorithm>
#include <cctype>
#include <initializer_list>
#include <stdexcept>
#include <vector>

#include "lang/syntax.h"
#include "lang/tokens.h"

namespace lwc {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// The language a text reads as, by words only one of the two writes: GLSL's version line and
// built-ins, HLSL's semantics, registers and resources, then each one's vector types; none when
// the text has neither.
std::optional<Lang> language_of_text(std::string_view text) {
  auto has = [&](std::initializer_list<const char*> words) {
    return std::any_of(words.begin(), words.end(), [&](const char* w) { return text.find(w) != std::string_view::npos; });
  };
  if (has({"#version", "gl_Position", "gl_FragColor", "gl_FragCoord", "gl_GlobalInvocationID"})) return Lang::glsl;
  if (reads_as_hlsl(text) || has({"Texture2D", "SamplerState", "float4 ", "float3 ", "float4x4", "mul("})) return Lang::hlsl;
  if (has({"vec4 ", "vec3 ", "mat4 ", "layout("})) return Lang::glsl;
  return std::nullopt;
}

std::optional<std::optional<FileFormat>> parse_format(std::string_view name) {
  if (name == "hlsl") return FileFormat{Lang::hlsl, Container::shader};
  if (name == "glsl") return FileFormat{Lang::glsl, Container::shader};
  if (name == "glsl-in-js") return FileFormat{Lang::glsl, Container::javascript};
  if (name == "none") return std::optional<FileFormat>();
  return std::nullopt;
}

}  // namespace

bool reads_as_hlsl(std::string_view text) {
  if (text.find("cbuffer ") != std::string_view::npos || text.find(": register(") != std::string_view::npos) return true;
  for (size_t at = text.find("SV_"); at != std::string_view::npos; at = text.find("SV_", at + 3)) {
    size_t before = text.find_last_not_of(" \t", at - 1);
    if (at > 0 && before != std::string_view::npos && text[before] == ':') return true;
  }
  return false;
}

bool holds_template_placeholders(std::string_view text) {
  for (size_t i = 0; i + 1 < text.size(); ++i) {
    if (text[i] == '/' && text[i + 1] == '/') i = std::min(text.find('\n', i), text.size());
    else if (text[i] == '/' && text[i + 1] == '*') i = std::min(text.find("*/", i + 2), text.size());
    else if (text[i] == '"') i = std::min(text.find('"', i + 1), text.size());
    else if (text[i] == '@' && ident_char(text[i + 1])) return true;
  }
  return false;
}

bool holds_effect_framework(std::string_view text) {
  auto word_at = [&](size_t at, std::string_view word) {
    return (at == 0 || !ident_char(text[at - 1])) && (at + word.size() == text.size() || !ident_char(text[at + word.size()]));
  };
  // The keyword opens a block (`technique Name {`, `sampler_state {`), not a word in a comment.
  auto opens_block = [&](size_t after) {
    size_t next = text.find_first_not_of(" \t\r\n", after);
    if (next != std::string_view::npos && ident_char(text[next])) {
      while (next < text.size() && ident_char(text[next])) ++next;
      next = text.find_first_not_of(" \t\r\n", next);
    }
    return next != std::string_view::npos && text[next] == '{';
  };
  for (std::string_view word : {"sampler_state", "technique", "technique10", "technique11"})
    for (size_t at = text.find(word); at != std::string_view::npos; at = text.find(word, at + 1))
      if (word_at(at, word) && opens_block(at + word.size())) return true;
  // A pass's `compile vs_3_0 Main()` (vs, ps, gs, hs, ds, cs).
  for (size_t at = text.find("compile"); at != std::string_view::npos; at = text.find("compile", at + 1)) {
    size_t profile = text.find_first_not_of(" \t", at + 7);
    if (word_at(at, "compile") && profile != std::string_view::npos && profile + 2 < text.size() &&
        std::string_view("vpghdc").find(text[profile]) != std::string_view::npos && text[profile + 1] == 's' && text[profile + 2] == '_')
      return true;
  }
  return false;
}

const FormatTable& FormatTable::defaults() {
  static const FormatTable table = [] {
    FormatTable t;
    // HLSL: Unreal, plain, D3DX effects and their headers, Unity's CG includes.
    for (const char* e : {".usf", ".ush", ".hlsl", ".hlsli", ".fx", ".fxh", ".cginc"}) t.set(e, "hlsl", "defaults");
    // GLSL: every stage glslang names, the iOS-style .vsh/.fsh, bgfx's .sc.
    for (const char* e : {".glsl", ".vert", ".frag", ".comp", ".geom", ".tesc", ".tese", ".mesh", ".task", ".rgen",
                          ".rchit", ".rmiss", ".rahit", ".rint", ".rcall", ".vsh", ".fsh", ".gsh", ".sc"})
      t.set(e, "glsl", "defaults");
    // Stage extensions both languages use (iOS GLSL, Diligent's and D3D samples' HLSL): the text
    // decides; without one, the language named here.
    for (const char* e : {".psh", ".csh"}) t.set(e, "hlsl", "defaults");
    for (const char* e : {".vsh", ".fsh", ".gsh", ".psh", ".csh"}) t.by_content_[e] = true;
    // GLSL in JavaScript and TypeScript: literals tagged or commented `glsl` (and every literal of
    // a .glsl.js/.glsl.ts file, lang/embedded.h).
    for (const char* e : {".js", ".mjs", ".cjs", ".jsx", ".ts", ".mts", ".cts", ".tsx"}) t.set(e, "glsl-in-js", "defaults");
    return t;
  }();
  return table;
}

void FormatTable::set(std::string_view extension, std::string_view format, std::string_view where) {
  if (extension.size() < 2 || extension[0] != '.' || extension.find('/') != std::string_view::npos)
    throw std::runtime_error(std::string(where) + ": extension \"" + std::string(extension) +
                             "\" must start with a dot, as in \".fxh\"");
  auto f = parse_format(format);
  if (!f)
    throw std::runtime_error(std::string(where) + ": extension \"" + std::string(extension) + "\": format must be hlsl, glsl, " +
                             "glsl-in-js or none (got \"" + std::string(format) + "\")");
  by_extension_[lower(extension)] = *f;
  by_content_.erase(lower(extension));  // a project that names it has decided
}

std::optional<ShaderEvidence> reads_as_shader(std::string_view text) {
  auto found = [&](std::string_view word) { return text.find(word) != std::string_view::npos; };
  if (found("SubShader") || found("CGPROGRAM") || found("HLSLPROGRAM")) return std::nullopt;
  std::vector<std::string_view> words;
  auto collect = [&](std::initializer_list<std::string_view> list, size_t most) {
    size_t taken = 0;
    for (std::string_view w : list)
      if (found(w) && taken < most) words.push_back(w), ++taken;
  };
  auto said = [&] {
    std::string out;
    for (std::string_view w : words) out += (out.empty() ? "`" : ", `") + std::string(w) + "`";
    return out;
  };
  // GLSL: a version line and a stage's built-ins or entry point.
  bool version = text.starts_with("#version") || found("\n#version");
  collect({"gl_Position", "gl_FragColor", "gl_FragCoord", "gl_GlobalInvocationID"}, 2);
  if (!words.empty() || (version && found("void main"))) {
    if (version) words.insert(words.begin(), "#version");
    return ShaderEvidence{"GLSL", said()};
  }
  // HLSL: what only HLSL writes, and its vector or resource types beside it.
  if (!reads_as_hlsl(text)) return std::nullopt;
  collect({"cbuffer", ": register(", "SV_Position", "SV_Target", "SV_DispatchThreadID", "[numthreads("}, 2);
  size_t hlsl_words = words.size();
  collect({"float4", "float3", "Texture2D", "SamplerState", "RWStructuredBuffer"}, 1);
  if (words.size() == hlsl_words) return std::nullopt;
  return ShaderEvidence{"HLSL", said()};
}

std::string FormatTable::mapped_extension(std::string_view path) const {
  size_t slash = path.rfind('/');
  std::string name = lower(slash == std::string_view::npos ? path : path.substr(slash + 1));
  for (size_t dot = name.find('.'); dot != std::string::npos; dot = name.find('.', dot + 1))
    if (dot > 0 && by_extension_.count(name.substr(dot))) return name.substr(dot);
  return {};
}

std::optional<FileFormat> FormatTable::for_path(std::string_view path, std::string_view text) const {
  size_t slash = path.rfind('/');
  std::string name = lower(slash == std::string_view::npos ? path : path.substr(slash + 1));
  // The longest extension first: `.glsl.js` before `.js`.
  for (size_t dot = name.find('.'); dot != std::string::npos; dot = name.find('.', dot + 1)) {
    if (dot == 0) continue;  // a hidden file's leading dot is not an extension
    auto it = by_extension_.find(name.substr(dot));
    if (it == by_extension_.end()) continue;
    if (it->second && by_content_.count(it->first))
      if (std::optional<Lang> lang = language_of_text(text)) return FileFormat{*lang, Container::shader};
    return it->second;
  }
  return std::nullopt;
}

std::string FormatTable::extensions() const {
  std::string out;
  for (const auto& [ext, format] : by_extension_)
    if (format) out += (out.empty() ? "" : ", ") + ext;
  return out;
}

}  // namespace lwc
