#pragma once
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/finding.h"
#include "core/source.h"
#include "fix/scene.h"
#include "lang/formats.h"
#include "lang/syntax.h"
#include "world/model.h"

namespace lwc {

struct AnalyzeOptions {
  std::optional<Lang> lang;              // overrides the extension
  const FormatTable* formats = nullptr;  // which extensions are shaders (default: FormatTable::defaults())
  std::set<std::string> select;          // empty: every rule
  std::set<std::string> ignore;
  std::map<std::string, Severity> severity;  // per-rule overrides
  nlohmann::json world_sources = nlohmann::json::array();  // the project's extra sources
  const FileSummary* includes = nullptr;  // what the file's #includes declare
  MacroTable macros;                      // the project's macros (.lwcport.json "macros")
  bool lint_library = false;              // report in the LWC libraries' own definitions too
  std::optional<UnrealEra> unreal;        // the engine the project builds against (else inferred per file)
  size_t max_bytes = 16u << 20;          // larger files are skipped with a diagnostic
  SceneNumbers scene;                    // what the scene needs (the default: Unreal's full world)
  Strategy strategy = Strategy::automatic;

  bool enabled(const std::string& rule) const;
};

// Everything lwcport says about one buffer. Pure: no file system, no global state beyond the
// immutable rule data.
std::vector<Finding> analyze(const Source& source, const AnalyzeOptions& options);

// How a path is analysed (language, and whether its GLSL sits in a script), honouring the override.
std::optional<FileFormat> format_for(const Source& source, const AnalyzeOptions& options);
std::optional<Lang> language_for(const Source& source, const AnalyzeOptions& options);
// The shader code of a file: the file itself, or for a script its GLSL template literals read in
// place (a same-length text, blank outside them). No `lang` when it is not a shader lwcport knows;
// no literals in a script means no shader code.
struct ShaderCode {
  std::optional<Lang> lang;
  bool script = false;
  // A script's literals, each its own shader, and each read at the script's offsets (the rest of
  // the script blank).
  std::vector<Span> literals;
  std::vector<Source> views;
  // What to analyse: the file itself, or a script's literals one by one.
  std::vector<const Source*> units(const Source& file) const {
    if (!script) return {&file};
    std::vector<const Source*> out;
    for (const Source& v : views) out.push_back(&v);
    return out;
  }
  bool empty(const Source& file) const { return !lang || (file.text().size() > 0 && script && literals.empty()); }
};
ShaderCode shader_code(const Source& source, const AnalyzeOptions& options);
// False for a script (JavaScript, TypeScript) that holds no GLSL template literal: not linted.
bool holds_shader_code(const Source& source, const AnalyzeOptions& options);

// World-space data for a language plus extra sources, built once per distinct extra list.
const WorldData& world_data(Lang lang, const nlohmann::json& extra_sources);
// Naming conventions count as evidence in plain code and in Unreal code written for UE4 (what
// its own code uses, whatever engine it now builds against): UE5-era code says what is large
// through the engine's large-world types.
bool names_as_evidence(const Source& source, Lang lang);

// The paths a file #includes, in order, as written (a scan of its directive lines).
std::vector<std::string> include_paths(std::string_view text);

// An lwc-input finding: a problem with the file itself rather than its code.
Finding input_finding(Severity severity, uint32_t offset, std::string message, std::string hint);
Finding too_large_finding(size_t bytes, size_t limit);

}  // namespace lwc
