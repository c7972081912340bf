#include "shaderlib/engine_standins.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/embedded.h"

namespace fs = std::filesystem;

namespace lwc {
namespace {

// One row of lwcport's era tables (tool/shaderlib/src/unreal_*.txt): who holds the member (in
// unreal_view_members.txt `member` of the View uniform buffer, or `derived` by the engine's
// InstancedStereo.ush into the view state in UE 5; in unreal_uniform_buffers.txt the uniform
// buffer), its HLSL type, its name (with an array size, "Name[2]"; a path "A.B" for a member of a
// nested struct) and the eras that have it.
struct TableRow {
  std::string holder, type, name;
  std::vector<int> eras;
  bool in(UnrealEra era) const { return std::find(eras.begin(), eras.end(), static_cast<int>(era)) != eras.end(); }
  bool opaque() const {  // a resource: the view state holds none (the engine casts 0 to it)
    return type.find("Texture") != std::string::npos || type.find("Sampler") != std::string::npos ||
           type.find("Buffer") != std::string::npos;
  }
  std::string bare_name() const { return name.substr(0, name.find('[')); }
};

std::vector<TableRow> read_table(std::string_view file) {
  std::string_view text;
  for (const EmbeddedFile& f : embedded_shaderlib_files())
    if (f.name == file) text = f.text;
  std::vector<TableRow> out;
  std::istringstream lines{std::string(text)};
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    TableRow row;
    words >> row.holder >> row.type >> row.name;
    for (int era; words >> era;) row.eras.push_back(era);
    if (row.name.empty() || row.eras.empty()) throw std::logic_error(fmt::format("{}: bad row: {}", file, line));
    out.push_back(std::move(row));
  }
  return out;
}

const std::vector<TableRow>& view_members() {
  static const std::vector<TableRow> rows = read_table("unreal_view_members.txt");
  return rows;
}

const std::vector<TableRow>& buffer_members() {
  static const std::vector<TableRow> rows = read_table("unreal_uniform_buffers.txt");
  return rows;
}

// A uniform buffer's members as a tree: a path A.B is member B of a nested struct A.
struct MemberNode {
  std::string name;
  std::string type;  // a leaf's HLSL type, or "struct:Buffer"
  std::vector<MemberNode> children;  // in the table's order
  MemberNode& child(const std::string& child_name) {
    for (MemberNode& node : children)
      if (node.name == child_name) return node;
    children.push_back(MemberNode{child_name, "", {}});
    return children.back();
  }
};

// Writes the struct declarations of the other global uniform buffers of an era, each followed by
// a static instance: a buffer another one embeds (`struct:Name`) first, nested structs before
// the struct holding them; a `struct:Name` with no table of its own is left out.
class BufferWriter {
 public:
  explicit BufferWriter(UnrealEra era) {
    for (const TableRow& m : buffer_members()) {
      if (!m.in(era)) continue;
      if (m.type == "include") {
        includes_[m.holder].push_back(m.name);
        continue;
      }
      MemberNode* node = &buffers_[m.holder];
      for (size_t begin = 0, dot;; begin = dot + 1) {
        dot = m.name.find('.', begin);
        node = &node->child(m.name.substr(begin, dot == std::string::npos ? dot : dot - begin));
        if (dot == std::string::npos) break;
      }
      node->type = m.type;
    }
  }
  // Every buffer of the era, or one.
  std::string text(const std::string& only = "") {
    for (const auto& [buffer, node] : buffers_)
      if (only.empty() || buffer == only) write_buffer(buffer);
    return out_;
  }
  bool has(const std::string& buffer) const { return buffers_.count(buffer) > 0; }

 private:
  void write_buffer(const std::string& buffer) {
    if (!written_.insert(buffer).second) return;
    // Guarded as the engine's generated buffers are: a buffer a file includes on its own
    // (/Engine/Generated/UniformBuffers/<Name>.ush) and again through the list is declared once.
    std::string type = "FLwcport" + buffer;
    out_ += fmt::format("#ifndef __UniformBuffer_{0}_Definition__\n#define __UniformBuffer_{0}_Definition__\n", buffer);
    for (const std::string& header : includes_[buffer]) out_ += fmt::format("#include \"{}\"\n", header);
    write_struct(type, buffers_.at(buffer));
    out_ += fmt::format("static {} {};\n#endif\n", type, buffer);
  }
  void write_struct(const std::string& type, const MemberNode& node) {
    std::string body;
    for (const MemberNode& child : node.children) {
      const std::string& name = child.name;
      std::string member_type = child.type;
      if (!child.children.empty()) {
        member_type = type + "_" + name.substr(0, name.find('['));
        write_struct(member_type, child);
      } else if (child.type.starts_with("struct:")) {
        std::string embedded = child.type.substr(7);
        if (!buffers_.count(embedded)) continue;
        write_buffer(embedded);
        member_type = "FLwcport" + embedded;
      }
      body += fmt::format("\t{} {};\n", member_type, name);
    }
    out_ += fmt::format("struct {}\n{{\n{}}};\n", type, body);
  }
  std::map<std::string, MemberNode> buffers_;
  std::map<std::string, std::vector<std::string>> includes_;  // headers declaring structs a buffer holds
  std::set<std::string> written_;
  std::string out_;
};

std::vector<const TableRow*> members_of(UnrealEra era, bool derived) {
  std::vector<const TableRow*> out;
  for (const TableRow& m : view_members())
    if ((m.holder == "derived") == derived && m.in(era)) out.push_back(&m);
  return out;
}

// The first lines of a stand-in: what it stands for, and where lwcport took it from.
std::string standin_head(std::string_view what, UnrealEra era, std::string_view from) {
  return fmt::format("// lwcport's stand-in for {}, which Unreal's shader compiler generates ({});\n// {}.\n", what,
                     era_name(era), from);
}
constexpr std::string_view kViewTable = "from lwcport's table of the era (tool/shaderlib/src/unreal_view_members.txt), not the engine's text";
constexpr std::string_view kBufferTable =
    "from lwcport's table of the era (tool/shaderlib/src/unreal_uniform_buffers.txt), not the engine's text";

// The View uniform buffer as a struct: its members with the names shaders use (`View.Member`).
// Static, not a cbuffer: glslang's error recovery crashes on a missing member of a uniform struct
// that holds textures, and a build check only needs the names and types.
std::string view_buffer(UnrealEra era) {
  std::string out = standin_head("the View uniform buffer (/Engine/Generated/UniformBuffers/View.ush)", era, kViewTable);
  out += "#ifndef __UniformBuffer_View_Definition__\n#define __UniformBuffer_View_Definition__\nstruct FLwcportViewUniformBuffer\n{\n";
  for (const TableRow* m : members_of(era, false)) out += fmt::format("\t{} {};\n", m->type, m->name);
  return out + "};\nstatic FLwcportViewUniformBuffer View;\n#endif\n";
}

std::string instanced_view_buffer(UnrealEra era) {
  return standin_head("the InstancedView uniform buffer (the second eye's view, members as View's)", era, kViewTable) +
         "#include \"/Engine/Generated/UniformBuffers/View.ush\"\n"
         "#ifndef __UniformBuffer_InstancedView_Definition__\n#define __UniformBuffer_InstancedView_Definition__\n"
         "static FLwcportViewUniformBuffer InstancedView;\n#endif\n";
}

// ViewState (every member of View but its resources, plus what FinalizeViewState derives in UE 5)
// and the accessors that copy a view into it.
std::string instanced_stereo(UnrealEra era) {
  std::string out = standin_head("ViewState, GetPrimaryView and GetInstancedView (GeneratedInstancedStereo.ush)", era, kViewTable);
  // A derived member `Group.Member` is a member of a struct the view state holds (TileOffset).
  std::map<std::string, std::string> groups;
  for (const TableRow* m : members_of(era, true))
    if (size_t dot = m->name.find('.'); dot != std::string::npos)
      groups[m->name.substr(0, dot)] += fmt::format("\t{} {};\n", m->type, m->name.substr(dot + 1));
  for (const auto& [group, body] : groups) out += fmt::format("struct FLwcportViewState_{}\n{{\n{}}};\n", group, body);
  out += "struct ViewState\n{\n";
  for (bool derived : {false, true})
    for (const TableRow* m : members_of(era, derived))
      if (!m->opaque() && m->name.find('.') == std::string::npos) out += fmt::format("\t{} {};\n", m->type, m->name);
  for (const auto& [group, body] : groups) out += fmt::format("\tFLwcportViewState_{0} {0};\n", group);
  out += "};\n";
  bool finalize = era != UnrealEra::ue4;
  if (finalize) out += "void FinalizeViewState(inout ViewState InOutView);  // InstancedStereo.ush\n";
  for (std::string_view source : {"View", "InstancedView"}) {
    bool primary = source == "View";
    std::string signature = primary ? "GetPrimaryView()" : era == UnrealEra::ue5_4 ? "GetInstancedView(uint ViewIndex)" : "GetInstancedView()";
    out += fmt::format("ViewState {}\n{{\n\tViewState Result;\n", signature);
    for (const TableRow* m : members_of(era, false))
      if (!m->opaque()) out += fmt::format("\tResult.{0} = {1}.{0};\n", m->bare_name(), source);
    out += finalize ? "\tFinalizeViewState(Result);\n\treturn Result;\n}\n" : "\treturn Result;\n}\n";
  }
  return out;
}

}  // namespace

std::optional<UnrealEra> engine_shaders_era(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_regular_file(folder / "Private" / "Common.ush", ec)) return std::nullopt;
  if (fs::is_regular_file(folder / "Private" / "DoubleFloat.ush", ec)) return UnrealEra::ue5_4;
  if (fs::is_regular_file(folder / "Private" / "LargeWorldCoordinates.ush", ec)) return UnrealEra::ue5_0;
  return UnrealEra::ue4;
}

std::vector<std::pair<std::string, std::string>> engine_compile_defines(UnrealEra era) {
  // Shader Model 5 on D3D, rendered by the deferred renderer (the scene textures are bound).
  std::vector<std::pair<std::string, std::string>> out = {{"SM5_PROFILE", "1"}, {"COMPILER_HLSL", "1"}, {"SHADING_PATH_DEFERRED", "1"},
                                                           // A material's settings, at their defaults.
                                                           {"USE_DITHERED_LOD_TRANSITION_FROM_MATERIAL", "0"}};
  if (era == UnrealEra::ue5_4) {
    // A project's rendering settings, at their defaults: Substrate off, the working colour space sRGB.
    out.insert(out.end(), {{"SUBSTRATE_ENABLED", "0"}, {"WORKING_COLOR_SPACE_IS_SRGB", "1"},
                           // Materials' world-space vectors in DoubleFloat, the 5.4 era's type.
                           {"WSVECTOR_IS_DOUBLEFLOAT", "1"}});
  }
  if (era != UnrealEra::ue4) {
    // The render tile of the tile/offset types (2^21 cm), which the engine's C++ hands its shaders.
    out.insert(out.end(), {{"UE_LWC_RENDER_TILE_SIZE", "2097152.0"},
                           {"UE_LWC_RENDER_TILE_SIZE_SQRT", "1448.15468787004917"},
                           {"UE_LWC_RENDER_TILE_SIZE_RSQRT", "0.000690533966002527907"},
                           {"UE_LWC_RENDER_TILE_SIZE_RCP", "4.76837158203125e-07"},
                           {"UE_LWC_RENDER_TILE_SIZE_FMOD_PI", "0.0"},
                           {"UE_LWC_RENDER_TILE_SIZE_FMOD_2PI", "0.0"},
                           // A material's large-world setting, on by default.
                           {"MATERIAL_LWC_ENABLED", "1"}});
  }
  return out;
}

std::optional<std::string> generated_standin(std::string_view name, UnrealEra era) {
  if (name == "GeneratedUniformBuffers.ush")
    return standin_head("the global uniform buffers a shader may use (View, InstancedView and those the common headers read)", era, kBufferTable) +
           "#include \"/Engine/Generated/UniformBuffers/View.ush\"\n#include \"/Engine/Generated/UniformBuffers/InstancedView.ush\"\n" +
           BufferWriter(era).text();
  if (name == "UniformBuffers/View.ush") return view_buffer(era);
  if (name == "UniformBuffers/InstancedView.ush") return instanced_view_buffer(era);
  if (name == "GeneratedInstancedStereo.ush") return instanced_stereo(era);
  if (name == "VertexFactory.ush")  // the permutation of a static mesh
    return standin_head("the vertex factory a shader is compiled with", era, "the engine's own local (static mesh) vertex factory") +
           "#include \"/Engine/Private/LocalVertexFactory.ush\"\n";
  if (name.starts_with("UniformBuffers/") && name.ends_with(".ush")) {
    std::string buffer(name.substr(15, name.size() - 19));
    BufferWriter writer(era);
    if (writer.has(buffer)) return standin_head("a uniform buffer the engine declares in C++", era, kBufferTable) + writer.text(buffer);
  }
  return std::nullopt;
}

std::string material_standin(std::string_view material_template, UnrealEra era) {
  // The pixel material inputs and attributes a default material has (its output pins), widest
  // type first where eras differ: a use of fewer components still compiles.
  static const char* const kPixelInputs =
      "\tMaterialFloat3 EmissiveColor;\n\tMaterialFloat Opacity;\n\tMaterialFloat OpacityMask;\n\tMaterialFloat3 BaseColor;\n"
      "\tMaterialFloat Metallic;\n\tMaterialFloat Specular;\n\tMaterialFloat Roughness;\n\tMaterialFloat Anisotropy;\n"
      "\tMaterialFloat3 Normal;\n\tMaterialFloat3 Tangent;\n\tMaterialFloat4 Subsurface;\n\tMaterialFloat AmbientOcclusion;\n"
      "\tMaterialFloat3 Refraction;\n\tMaterialFloat PixelDepthOffset;\n\tuint ShadingModel;\n\tMaterialFloat Displacement;\n"
      "\tMaterialFloat3 ObjectNormal;\n";
  std::string out = standin_head("a material's shader code (/Engine/Generated/Material.ush)", era, "the engine's own material template, its blanks filled in by lwcport for a material with no expressions");
  out += "#line 1 \"/Engine/Private/MaterialTemplate.ush\"\n";
  std::string_view text = material_template;
  int line = 1;
  size_t done = 0;
  for (size_t at = text.find('%'); at != std::string_view::npos; at = text.find('%', at + 1)) {
    size_t end = at + 1;
    if (end < text.size() && text[end] == '{') end = text.find('}', end);
    else if (end >= text.size() || (text[end] != 's' && text[end] != 'd')) continue;  // a `%` that is not a blank (a modulo)
    if (end == std::string_view::npos) break;
    line += static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(done), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    size_t line_begin = text.rfind('\n', at);
    line_begin = line_begin == std::string_view::npos ? 0 : line_begin + 1;
    std::string_view head = text.substr(line_begin, at - line_begin);
    size_t next = text.find_first_not_of(" \t", end + 1);
    // What lies since the last statement or block: a struct's head when the blank is its members.
    size_t stop = text.find_last_of(";}", at);
    std::string_view above = stop == std::string_view::npos ? text.substr(0, at) : text.substr(stop + 1, at - stop - 1);
    std::string fill;
    if (head.find("#line") != std::string_view::npos) {
      fill = std::to_string(line + 1);  // the template's next line keeps its own number
    } else if (head.find("#define") != std::string_view::npos) {
      bool texcoords = head.find("TEXCOORDS") != std::string_view::npos || head.find("TEX_COORD") != std::string_view::npos;
      fill = std::to_string(texcoords ? 1 : 0);
    } else if (next != std::string_view::npos && text[next] == ';') {
      fill = "return 0";
    } else if (above.find("struct FPixelMaterialInputs") != std::string_view::npos ||
               above.find("struct FMaterialAttributes") != std::string_view::npos) {
      fill = kPixelInputs;
    } else if (text.substr(at, end + 1 - at) == "%{material_declarations}") {
      // From 5.4 the material's attributes struct comes with its declarations.
      fill = std::string("struct FMaterialAttributes\n{\n") + kPixelInputs + "};\n";
    }
    out.append(text.substr(done, at - done));
    out += fill;
    // Lines a blank's code adds are not the template's: later messages keep its line numbers.
    if (fill.find('\n') != std::string::npos) out += fmt::format("#line {}", line + 1);
    done = end + 1;
  }
  out.append(text.substr(done));
  return out;
}


}  // namespace lwc
