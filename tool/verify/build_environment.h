#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lang/syntax.h"
#include "verify/compile.h"
#include "world/era.h"

namespace lwc {

struct ProjectConfig;
class IncludeSummaries;

// How lwcport compiles a file of a project (verify, fix --verify, --check-build): its includes
// resolved as lint resolves them, lwcport's library from memory, the build's defines and forced
// includes. Unreal code compiles against lwcport's stub of its era, the engine headers it stands
// for answered by the stub; or, with "engine-shaders", against the engine's own headers, lwcport
// standing in only for what the shader compiler generates (shaderlib/engine_standins.h).
struct BuildEnvironment {
  bool unreal = false;               // Unreal code (.usf, .ush)
  std::optional<UnrealEra> engine;   // compiled against the engine's headers, of this era
  IncludeResolver include;
  std::vector<std::pair<std::string, std::string>> defines;
  std::vector<std::string> force_includes;
};
// `text`: the file's own text, which says what context a header expects from its includers.
BuildEnvironment build_environment(const std::filesystem::path& path, const std::string& display, std::string_view text, Lang lang,
                                   std::shared_ptr<const ProjectConfig> config, IncludeSummaries& includes);

}  // namespace lwc
