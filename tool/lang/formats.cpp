#include "lang/formats.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "lang/syntax.h"

namespace lwc {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::optional<std::optional<FileFormat>> parse_format(std::string_view name) {
  if (name == "hlsl") return FileFormat{Lang::hlsl, Container::shader};
  if (name == "glsl") return FileFormat{Lang::glsl, Container::shader};
  if (name == "glsl-in-js") return FileFormat{Lang::glsl, Container::javascript};
  if (name == "none") return std::optional<FileFormat>();
  return std::nullopt;
}

}  // namespace

const FormatTable& FormatTable::defaults() {
  static const FormatTable table = [] {
    FormatTable t;
    // HLSL: Unreal, plain, D3DX effects and their headers, Unity's CG includes.
    for (const char* e : {".usf", ".ush", ".hlsl", ".hlsli", ".fx", ".fxh", ".cginc"}) t.set(e, "hlsl", "defaults");
    // GLSL: every stage glslang names, the iOS-style .vsh/.fsh, bgfx's .sc.
    for (const char* e : {".glsl", ".vert", ".frag", ".comp", ".geom", ".tesc", ".tese", ".mesh", ".task", ".rgen",
                          ".rchit", ".rmiss", ".rahit", ".rint", ".rcall", ".vsh", ".fsh", ".sc"})
      t.set(e, "glsl", "defaults");
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
}

std::optional<FileFormat> FormatTable::for_path(std::string_view path) const {
  size_t slash = path.rfind('/');
  std::string name = lower(slash == std::string_view::npos ? path : path.substr(slash + 1));
  // The longest extension first: `.glsl.js` before `.js`.
  for (size_t dot = name.find('.'); dot != std::string::npos; dot = name.find('.', dot + 1)) {
    if (dot == 0) continue;  // a hidden file's leading dot is not an extension
    auto it = by_extension_.find(name.substr(dot));
    if (it != by_extension_.end()) return it->second;
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
