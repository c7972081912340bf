#include "shaderlib/engine_standins.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/embedded.h"

namespace fs = std::filesystem;

namespace lwc {
namespace {

std::string_view embedded_text(std::string_view name) {
  for (const EmbeddedFile& f : embedded_shaderlib_files())
    if (f.name == name) return f.text;
  throw std::logic_error("shader library file not embedded: " + std::string(name));
}

// One row of unreal_view_members.txt: a member of the View uniform buffer, or one the engine's
// InstancedStereo.ush derives into the view state from those (FinalizeViewState, UE 5.x).
struct ViewMember {
  bool derived = false;
  std::string type, name;  // name may carry an array size: "Name[2]"
  std::vector<int> eras;
  bool opaque() const {  // a resource: the view state holds none (the engine casts 0 to it)
    return type.find("Texture") != std::string::npos || type.find("Sampler") != std::string::npos ||
           type.find("Buffer") != std::string::npos;
  }
  std::string bare_name() const { return name.substr(0, name.find('[')); }
};

const std::vector<ViewMember>& view_members() {
  static const std::vector<ViewMember> members = [] {
    std::vector<ViewMember> out;
    std::istringstream lines{std::string(embedded_text("unreal_view_members.txt"))};
    for (std::string line; std::getline(lines, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream words(line);
      std::string kind;
      ViewMember m;
      words >> kind >> m.type >> m.name;
      if (kind != "member" && kind != "derived") throw std::logic_error("unreal_view_members.txt: bad row: " + line);
      m.derived = kind == "derived";
      for (int era; words >> era;) m.eras.push_back(era);
      out.push_back(std::move(m));
    }
    return out;
  }();
  return members;
}

// One row of unreal_uniform_buffers.txt: a member of another global uniform buffer.
struct BufferMember {
  std::string buffer, type, name;
  std::vector<int> eras;
};

const std::vector<BufferMember>& buffer_members() {
  static const std::vector<BufferMember> members = [] {
    std::vector<BufferMember> out;
    std::istringstream lines{std::string(embedded_text("unreal_uniform_buffers.txt"))};
    for (std::string line; std::getline(lines, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream words(line);
      BufferMember m;
      words >> m.buffer >> m.type >> m.name;
      for (int era; words >> era;) m.eras.push_back(era);
      out.push_back(std::move(m));
    }
    return out;
  }();
  return members;
}

// The other global uniform buffers of an era, each a struct and a static instance of it.
std::string other_buffers(UnrealEra era) {
  std::map<std::string, std::string> bodies;
  for (const BufferMember& m : buffer_members())
    if (std::find(m.eras.begin(), m.eras.end(), static_cast<int>(era)) != m.eras.end())
      bodies[m.buffer] += fmt::format("\t{} {};\n", m.type, m.name);
  std::string out;
  for (const auto& [buffer, body] : bodies)
    out += fmt::format("#ifndef __UniformBuffer_{0}_Definition__\n#define __UniformBuffer_{0}_Definition__\nstruct FLwcport{0}\n{{\n{1}}};\n"
                       "static FLwcport{0} {0};\n#endif\n", buffer, body);
  return out;
}

std::vector<const ViewMember*> members_of(UnrealEra era, bool derived) {
  std::vector<const ViewMember*> out;
  for (const ViewMember& m : view_members())
    if (m.derived == derived && std::find(m.eras.begin(), m.eras.end(), static_cast<int>(era)) != m.eras.end()) out.push_back(&m);
  return out;
}

std::string standin_head(std::string_view what, UnrealEra era) {
  return fmt::format("// lwcport's stand-in for {}, which Unreal's shader compiler generates ({}); from lwcport's\n"
                     "// table of the era (tool/shaderlib/src/unreal_view_members.txt), not the engine's text.\n",
                     what, era_name(era));
}

// The View uniform buffer as a struct: its members with the names shaders use (`View.Member`).
// Static, not a cbuffer: glslang's error recovery crashes on a missing member of a uniform struct
// that holds textures, and a build check only needs the names and types.
std::string view_buffer(UnrealEra era) {
  std::string out = standin_head("the View uniform buffer (/Engine/Generated/UniformBuffers/View.ush)", era);
  out += "#ifndef __UniformBuffer_View_Definition__\n#define __UniformBuffer_View_Definition__\nstruct FLwcportViewUniformBuffer\n{\n";
  for (const ViewMember* m : members_of(era, false)) out += fmt::format("\t{} {};\n", m->type, m->name);
  return out + "};\nstatic FLwcportViewUniformBuffer View;\n#endif\n";
}

std::string instanced_view_buffer(UnrealEra era) {
  return standin_head("the InstancedView uniform buffer (the second eye's view, members as View's)", era) +
         "#include \"/Engine/Generated/UniformBuffers/View.ush\"\n"
         "#ifndef __UniformBuffer_InstancedView_Definition__\n#define __UniformBuffer_InstancedView_Definition__\n"
         "static FLwcportViewUniformBuffer InstancedView;\n#endif\n";
}

// ViewState (every member of View but its resources, plus what FinalizeViewState derives in UE 5)
// and the accessors that copy a view into it.
std::string instanced_stereo(UnrealEra era) {
  std::string out = standin_head("ViewState, GetPrimaryView and GetInstancedView (GeneratedInstancedStereo.ush)", era);
  out += "struct ViewState\n{\n";
  for (bool derived : {false, true})
    for (const ViewMember* m : members_of(era, derived))
      if (!m->opaque()) out += fmt::format("\t{} {};\n", m->type, m->name);
  out += "};\n";
  bool finalize = era != UnrealEra::ue4;
  if (finalize) out += "void FinalizeViewState(inout ViewState InOutView);  // InstancedStereo.ush\n";
  for (std::string_view source : {"View", "InstancedView"}) {
    bool primary = source == "View";
    std::string signature = primary ? "GetPrimaryView()" : era == UnrealEra::ue5_4 ? "GetInstancedView(uint ViewIndex)" : "GetInstancedView()";
    out += fmt::format("ViewState {}\n{{\n\tViewState Result;\n", signature);
    for (const ViewMember* m : members_of(era, false))
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
  std::vector<std::pair<std::string, std::string>> out = {{"SM5_PROFILE", "1"}, {"COMPILER_HLSL", "1"}};
  if (era == UnrealEra::ue5_4) {
    // A project's rendering settings, at their defaults: Substrate off, the working colour space sRGB.
    out.insert(out.end(), {{"SUBSTRATE_ENABLED", "0"}, {"WORKING_COLOR_SPACE_IS_SRGB", "1"}});
  }
  if (era != UnrealEra::ue4) {
    // The render tile of the tile/offset types (2^21 cm), which the engine's C++ hands its shaders.
    out.insert(out.end(), {{"UE_LWC_RENDER_TILE_SIZE", "2097152.0"},
                           {"UE_LWC_RENDER_TILE_SIZE_SQRT", "1448.15468787004917"},
                           {"UE_LWC_RENDER_TILE_SIZE_RSQRT", "0.000690533966002527907"},
                           {"UE_LWC_RENDER_TILE_SIZE_RCP", "4.76837158203125e-07"},
                           {"UE_LWC_RENDER_TILE_SIZE_FMOD_PI", "0.0"},
                           {"UE_LWC_RENDER_TILE_SIZE_FMOD_2PI", "0.0"}});
  }
  return out;
}

std::optional<std::string> generated_standin(std::string_view name, UnrealEra era) {
  if (name == "GeneratedUniformBuffers.ush")
    return standin_head("the global uniform buffers a shader may use (View, InstancedView and those the common headers read)", era) +
           "#include \"/Engine/Generated/UniformBuffers/View.ush\"\n#include \"/Engine/Generated/UniformBuffers/InstancedView.ush\"\n" +
           other_buffers(era);
  if (name == "UniformBuffers/View.ush") return view_buffer(era);
  if (name == "UniformBuffers/InstancedView.ush") return instanced_view_buffer(era);
  if (name == "GeneratedInstancedStereo.ush") return instanced_stereo(era);
  return std::nullopt;
}

std::string generated_not_stood_in(std::string_view name) {
  if (generated_standin(name, UnrealEra::ue5_4)) return "";
  if (name == "Material.ush") return "the material template, which the engine fills in per material";
  if (name == "VertexFactory.ush") return "the vertex factory a permutation compiles with";
  if (name.starts_with("UniformBuffers/")) return "a uniform buffer declared in the engine's C++, which lwcport has no table for";
  return "a header the engine generates, which lwcport has no table for";
}

}  // namespace lwc
