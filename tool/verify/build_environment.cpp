#include "verify/build_environment.h"

#include <algorithm>
#include <set>

#include "project/config.h"
#include "project/files.h"
#include "project/includes.h"
#include "shaderlib/engine_standins.h"
#include "shaderlib/shaderlib.h"

namespace fs = std::filesystem;

namespace lwc {
namespace {

// The engine headers lwcport's Unreal stub stands for when the engine's own folder is a virtual
// root: the platform layer (written for DXC and each platform's compiler), the LWC libraries
// (the stub carries lwcport's, with the same names) and the view the shader compiler generates.
// The engine's other headers are read as they are, and a kernel takes from them only what its
// function needs.
bool stands_for_engine_header(const std::string& name, const fs::path& resolved, const ProjectConfig& config) {
  bool engine = name.starts_with("/Engine/");
  for (const auto& [prefix, folder] : config.virtual_roots)
    if (prefix == "/Engine/") {
      std::string rel = resolved.lexically_normal().lexically_relative(folder.lexically_normal()).generic_string();
      engine |= !rel.empty() && !rel.starts_with("..");
    }
  static const std::set<std::string> stubbed = {"Platform.ush", "LargeWorldCoordinates.ush", "DoubleFloat.ush", "LWCOperations.ush",
                                                "InstancedStereo.ush", "SceneData.ush"};
  return engine && (stubbed.count(resolved.filename().string()) || name.starts_with("/Engine/Generated/"));
}

}  // namespace

BuildEnvironment build_environment(const fs::path& path, const std::string& display, std::string_view text, Lang lang,
                                   std::shared_ptr<const ProjectConfig> config, IncludeSummaries& includes) {
  BuildEnvironment env;
  env.unreal = display.ends_with(".usf") || display.ends_with(".ush");
  env.defines = config->defines_for(path);
  env.force_includes = config->force_includes;
  if (env.unreal && config->engine_era) {
    env.engine = config->engine_era;
    // The shader compiler's macros first; the project's own defines override them by name.
    auto defines = engine_compile_defines(*env.engine);
    std::erase_if(defines, [&](const auto& d) {
      return std::any_of(env.defines.begin(), env.defines.end(), [&](const auto& own) { return own.first == d.first; });
    });
    env.defines.insert(env.defines.begin(), defines.begin(), defines.end());
    // An engine header is compiled after Common.ush, as every shader that includes it is, and a
    // vertex factory's or a material's helper after the material template it takes its types from.
    if (env.force_includes.empty() && display.ends_with(".ush")) {
      env.force_includes.push_back("/Engine/Private/Common.ush");
      bool material_types = text.find("FMaterialVertexParameters") != std::string_view::npos ||
                            text.find("FMaterialPixelParameters") != std::string_view::npos;
      if (material_types && text.find("struct FMaterialPixelParameters") == std::string_view::npos)
        env.force_includes.push_back("/Engine/Generated/Material.ush");
    }
  }
  // An include is named by its real path (relative to the working folder when under it), so an
  // include inside it resolves from its own folder and errors show where it really is.
  std::optional<UnrealEra> engine = env.engine;
  env.include = [&includes, path, display, config, lang, engine](const std::string& name, const std::string& from) -> std::optional<IncludedFile> {
    if (name == library_file_name(lang)) return IncludedFile{name, full_library_text(lang)};
    if (engine && name == "/Engine/Generated/Material.ush") {  // the engine's template, filled in
      std::optional<fs::path> p = includes.resolve("/Engine/Private/MaterialTemplate.ush", path, *config);
      ReadResult r = p ? read_file(*p, config->max_file_bytes) : ReadResult{};
      if (!p || !r.error.empty()) return std::nullopt;
      return IncludedFile{name, material_standin(r.text, *engine)};
    }
    if (engine && name.starts_with("/Engine/Generated/")) {
      std::optional<std::string> standin = generated_standin(std::string_view(name).substr(18), *engine);
      if (!standin) return std::nullopt;
      return IncludedFile{name, std::move(*standin)};
    }
    fs::path includer = from.empty() || from == display ? path : fs::path(from);
    std::optional<fs::path> p = includes.resolve(name, includer, *config);
    if (p && !engine && stands_for_engine_header(name, *p, *config)) return IncludedFile{name, unreal_engine_header_text(true)};
    if (p) {
      ReadResult r = read_file(*p, config->max_file_bytes);
      std::error_code ec;
      fs::path shown = p->lexically_normal();
      if (fs::path near = fs::proximate(shown, ec); !ec && !near.empty() && *near.begin() != "..") shown = near;
      if (r.error.empty()) return IncludedFile{shown.string(), std::move(r.text)};
    }
    // Without the engine's headers, lwcport's stub answers for the engine.
    if (!engine && name.starts_with("/Engine/")) return IncludedFile{name, unreal_engine_header_text(false)};
    return std::nullopt;
  };
  return env;
}

}  // namespace lwc
