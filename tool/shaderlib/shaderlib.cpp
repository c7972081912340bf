#include "shaderlib/shaderlib.h"

#include "lang/tokens.h"

#include <cctype>
#include <map>
#include <stdexcept>
#include <vector>

#include "core/embedded.h"

namespace lwc {
namespace {

struct Block {
  std::string name;
  std::string text;                // instantiated for the language, every width
  std::set<std::string> defines;   // type and function names declared at the top level
  std::set<std::string, std::less<>> uses;  // identifiers anywhere in the text
};

std::string_view embedded(std::string_view name) {
  for (const EmbeddedFile& f : embedded_shaderlib_files())
    if (f.name == name) return f.text;
  throw std::logic_error("shader library file not embedded: " + std::string(name));
}

void replace_all(std::string& text, std::string_view from, std::string_view to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

// Replaces whole words only.
void replace_word(std::string& text, std::string_view from, std::string_view to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    bool starts = at == 0 || !ident_char(text[at - 1]);
    bool ends = at + from.size() == text.size() || !ident_char(text[at + from.size()]);
    if (starts && ends) {
      text.replace(at, from.size(), to);
      at += to.size();
    } else {
      at += from.size();
    }
  }
}

std::string instantiate(std::string text, Lang lang, int width) {
  static const char* hlsl_types[] = {"float", "float2", "float3", "float4"};
  static const char* glsl_types[] = {"float", "vec2", "vec3", "vec4"};
  static const char* pair_types[] = {"FDFScalar", "FDFVector2", "FDFVector3", "FDFVector4"};
  std::string f = (lang == Lang::hlsl ? hlsl_types : glsl_types)[width - 1];
  std::string make = width == 1 ? "MakeDFScalar" : "MakeDFVector" + std::to_string(width);
  std::string zero = lang == Lang::hlsl ? "(" + f + ")0" : (width == 1 ? "0.0" : f + "(0.0)");
  replace_all(text, "{F}", f);
  replace_all(text, "{DF}", pair_types[width - 1]);
  replace_all(text, "{MAKE}", make);
  replace_all(text, "{ZERO}", zero);
  replace_all(text, "{N}", std::to_string(width));
  return text;
}

// Names declared at the top level: `struct X`, and `... X(` on a line that starts a declaration.
std::set<std::string> declared_names(std::string_view text) {
  std::set<std::string> out;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    if (line.empty() || !std::isalpha(static_cast<unsigned char>(line[0]))) continue;
    if (line.rfind("struct ", 0) == 0) {
      size_t b = 7, e = b;
      while (e < line.size() && ident_char(line[e])) ++e;
      out.emplace(line.substr(b, e - b));
      continue;
    }
    size_t paren = line.find('(');
    if (paren == std::string_view::npos) continue;
    size_t e = paren, b = e;
    while (b > 0 && ident_char(line[b - 1])) --b;
    if (b < e) out.emplace(line.substr(b, e - b));
  }
  return out;
}

// Parses the template into blocks for one language, in file order.
std::vector<Block> load_blocks(Lang lang) {
  std::string_view source = embedded("doublefloat.lwclib");
  std::vector<Block> blocks;
  const std::string marker = "// @block ";
  size_t at = source.find(marker);
  while (at != std::string_view::npos) {
    size_t header_end = source.find('\n', at);
    size_t next = source.find(marker, header_end);
    std::string_view header = source.substr(at + marker.size(), header_end - at - marker.size());
    std::string_view body = source.substr(header_end + 1, (next == std::string_view::npos ? source.size() : next) - header_end - 1);
    at = next;

    std::string name, widths = "0";
    bool wanted = true;
    size_t pos = 0;
    while (pos < header.size()) {
      size_t space = header.find(' ', pos);
      std::string_view word = header.substr(pos, space == std::string_view::npos ? std::string_view::npos : space - pos);
      pos = space == std::string_view::npos ? header.size() : space + 1;
      if (word.rfind("widths=", 0) == 0) widths = std::string(word.substr(7));
      else if (word.rfind("lang=", 0) == 0) wanted = word.substr(5) == lang_name(lang);
      else if (name.empty()) name = std::string(word);
    }
    if (!wanted) continue;
    Block block{name, {}, {}, {}};
    for (char w : widths) {
      std::string text = w == '0' ? std::string(body) : instantiate(std::string(body), lang, w - '0');
      if (lang == Lang::glsl && name != "prelude") replace_word(text, "precise", "LWC_PRECISE");
      block.text += text;
    }
    while (block.text.size() >= 2 && block.text.ends_with("\n\n")) block.text.pop_back();
    block.defines = declared_names(block.text);
    block.uses = identifiers(block.text);
    blocks.push_back(std::move(block));
  }
  return blocks;
}

const std::vector<Block>& blocks_for(Lang lang) {
  static const std::vector<Block> hlsl = load_blocks(Lang::hlsl);
  static const std::vector<Block> glsl = load_blocks(Lang::glsl);
  return lang == Lang::hlsl ? hlsl : glsl;
}

constexpr std::string_view kWrittenMarker = "Written by lwcport";

std::string header(Lang lang) {
  std::string guard = lang == Lang::hlsl ? "LWC_DOUBLEFLOAT_HLSL" : "LWC_DOUBLEFLOAT_GLSL";
  return "// " + library_file_name(lang) +
         ": DoubleFloat (High + Low float pairs) for Large World Coordinates.\n"
         "// " + std::string(kWrittenMarker) + " for the code that includes it; regenerate with `lwcport fix`\n"
         "// rather than editing, so the next fix keeps what it needs.\n"
         "#ifndef " + guard + "\n#define " + guard + "\n\n";
}

}  // namespace

std::string library_file_name(Lang lang) {
  return lang == Lang::hlsl ? "lwc_doublefloat.hlsl" : "lwc_doublefloat.glsl";
}

bool is_written_library(std::string_view text) {
  std::string_view head = text.substr(0, 200);
  return head.starts_with("// lwc_doublefloat.") && head.find(kWrittenMarker) != std::string_view::npos;
}

std::optional<std::string> library_file_text(Lang lang, const std::set<std::string>& names, const std::optional<std::string>& existing) {
  if (existing && !is_written_library(*existing)) return std::nullopt;
  std::set<std::string> all = names;
  if (existing) all.merge(library_names_used(lang, *existing));
  return library_text(lang, all);
}

std::string library_text(Lang lang, const std::set<std::string>& names) {
  const std::vector<Block>& blocks = blocks_for(lang);
  // Close the wanted set over the blocks' uses.
  std::vector<bool> keep(blocks.size(), false);
  std::set<std::string> wanted = names;
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t i = 0; i < blocks.size(); ++i) {
      if (keep[i]) continue;
      bool needed = blocks[i].name == "prelude";
      for (const std::string& d : blocks[i].defines) needed = needed || wanted.count(d);
      if (!needed) continue;
      keep[i] = grew = true;
      wanted.insert(blocks[i].uses.begin(), blocks[i].uses.end());
    }
  }
  // The template lists every block after the blocks it uses, so file order is dependency order.
  std::string out = header(lang);
  for (size_t i = 0; i < blocks.size(); ++i)
    if (keep[i]) out += blocks[i].text + "\n\n";
  out += "#endif\n";
  return out;
}

std::string full_library_text(Lang lang) {
  std::set<std::string> all;
  for (const Block& b : blocks_for(lang)) all.insert(b.defines.begin(), b.defines.end());
  return library_text(lang, all);
}

std::set<std::string> library_names_used(Lang lang, std::string_view code) {
  std::set<std::string> used;
  std::set<std::string, std::less<>> words = identifiers(code);
  for (const Block& b : blocks_for(lang))
    for (const std::string& d : b.defines)
      if (words.count(d)) used.insert(d);
  return used;
}

std::string unreal_engine_header_text(bool engine_headers_read) {
  return (engine_headers_read ? "#define LWCPORT_READS_ENGINE_HEADERS 1\n" : "") + std::string(embedded("unreal_engine_header.ush"));
}

std::string unreal_environment_text(std::string_view code, const std::string& library) {
  // A struct or engine function the file declares itself (a copy of an engine header's) is left
  // out of the stub.
  static const std::set<std::string, std::less<>> copied_functions = {"TransformLocalToWorld", "TransformLocalToTranslatedWorld",
                                                                      "SvPositionToWorld", "SvPositionToTranslatedWorld",
                                                                      "ComputeDirectionalLightStaticShadowing", "ComputeDirectionalLightDynamicShadowing",
                                                                      "GetDistanceToNearestSurfaceGlobal", "ScreenAlignedPosition", "Rand3DPCG16",
                                                                      "TransformLocalPositionToWorld"};
  TokenText tokens(code);
  bool material_parameters = false, light_data = false;
  std::set<std::string, std::less<>> defined;
  for (size_t i = 0; i + 1 < tokens.size(); ++i) {
    if (i + 2 < tokens.size() && tokens[i + 2] == "(" && copied_functions.count(tokens[i + 1]) &&
        (tokens[i].starts_with("float") || tokens[i].starts_with("uint") || tokens[i].starts_with("F")))
      defined.insert(std::string(tokens[i + 1]));
    light_data |= tokens[i] == "float4x4" && tokens[i + 1] == "LightFunctionWorldToLight";
    if (tokens[i] != "struct") continue;
    material_parameters |= tokens[i + 1] == "FMaterialPixelParameters";
    light_data |= tokens[i + 1] == "FDeferredLightData" || tokens[i + 1] == "FSimpleDeferredLightData";
  }
  std::string own;
  for (const std::string& name : defined) own += "#define LWCPORT_FILE_DEFINES_" + name + " 1\n";
  return (library.empty() ? full_library_text(Lang::hlsl) : library) + "\n" + own +
         (material_parameters ? "#define LWCPORT_FILE_DECLARES_MATERIAL_PARAMETERS 1\n" : "") +
         (light_data ? "#define LWCPORT_FILE_DECLARES_LIGHT_DATA 1\n" : "") + std::string(embedded("unreal_stub.ush"));
}

}  // namespace lwc
