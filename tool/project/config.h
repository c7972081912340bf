#pragma once
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/finding.h"
#include "lang/formats.h"
#include "lang/macros.h"
#include "rules/analyze.h"
#include "world/era.h"

namespace lwc {

// One .lwcport.json: settings for the files under its folder.
struct ProjectConfig {
  std::filesystem::path dir;  // the folder holding the file ("" for the built-in defaults)
  std::map<std::string, Severity> severity;
  std::vector<std::string> select, ignore;
  std::vector<std::filesystem::path> include_dirs;
  std::vector<std::pair<std::string, std::filesystem::path>> virtual_roots;  // "/Engine/" -> folder
  std::vector<std::string> exclude;  // .gitignore-style patterns, relative to dir
  nlohmann::json world_sources = nlohmann::json::array();
  size_t max_file_bytes = 16u << 20;
  double max_parse_seconds = 30;  // the parser's budget per file
  std::vector<std::string> warnings;  // settings that are valid but look wrong, each a sentence
  MacroTable macros;  // macros used as syntax, by use (lang/macros.h)
  std::optional<UnrealEra> unreal;  // the engine the project builds against (else inferred per file)
  // The engine's own Shaders folder ("engine-shaders"), and the era its headers hold: verify and
  // --check-build then compile against its headers, lwcport standing in for what the shader
  // compiler generates (shaderlib/engine_standins.h). Unset, or no era when it is not one.
  std::optional<std::filesystem::path> engine_shaders;
  std::optional<UnrealEra> engine_era;
  FormatTable formats = FormatTable::defaults();  // which extensions are shaders, and how
  bool lint_library = false;        // report inside the LWC libraries' own definitions
  // The host subtracts a render origin (or the camera) from every position before upload: the
  // world data the tables name by convention is relative to it (`"host-rebases": true`).
  bool host_rebases = false;
  std::string help_uri_base;  // where the rule pages are published (ends in '/'); "" for the installed pages
  nlohmann::json host = nlohmann::json::object();  // lwcport host: additions to rules/host-world.json
  // Macros the build defines (Unreal's ModifyCompilationEnvironment, -D flags), for where lwcport
  // compiles code: verify, fix --verify and --check-build. Name -> value, in order.
  using Defines = std::vector<std::pair<std::string, std::string>>;
  Defines defines;
  // Defines for some files only: .gitignore-style patterns relative to dir; later entries win.
  struct PathDefines {
    std::vector<std::string> files;
    Defines defines;
  };
  std::vector<PathDefines> overrides;

  // Parses a config's text; throws std::runtime_error naming the file and the problem.
  static ProjectConfig parse(const std::filesystem::path& file, const std::string& text);
  bool excluded(const std::filesystem::path& path, bool is_dir) const;
  // Headers included ahead of every HLSL file verify or --check-build compiles, as a compiler's
  // forced include (`-include`, /FI): the context a material custom-node include or a shader built
  // into a generated one gets from its includer (`"/Engine/Private/Common.ush"`).
  std::vector<std::string> force_includes;
  // The defines for one file: `defines`, then each override whose pattern matches it.
  Defines defines_for(const std::filesystem::path& file) const;
};

// Finds the nearest .lwcport.json upward from a folder, loading each at most once.
class ConfigFinder {
 public:
  ConfigFinder() = default;
  // Every folder gets `fixed` (`--config FILE`, or the built-in defaults for `--isolated`).
  explicit ConfigFinder(std::shared_ptr<const ProjectConfig> fixed) : fixed_(std::move(fixed)) {}
  // Reads and parses one config file; throws std::runtime_error naming it.
  static std::shared_ptr<const ProjectConfig> read(const std::filesystem::path& file);
  // Throws std::runtime_error for a config that cannot be read or parsed.
  std::shared_ptr<const ProjectConfig> for_dir(const std::filesystem::path& dir);
  // Each config read so far, once.
  std::vector<std::shared_ptr<const ProjectConfig>> loaded();

 private:
  std::mutex mutex_;
  std::map<std::filesystem::path, std::shared_ptr<const ProjectConfig>> by_dir_;
  std::shared_ptr<const ProjectConfig> fixed_;
};

// .gitignore-style match of a pattern against a path relative to the pattern's folder.
bool gitignore_match(std::string_view pattern, std::string_view relative, bool is_dir);

// What the project's settings say about analysing its files (rules, severities, world sources,
// macros, engine, formats, limits): what every face starts from before its own flags.
AnalyzeOptions analysis_options(const ProjectConfig& config);

}  // namespace lwc
