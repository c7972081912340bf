#pragma once
#include <functional>
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

struct RuleInfo;

struct AnalyzeOptions {
  std::optional<Lang> lang;              // overrides the extension
  const FormatTable* formats = nullptr;  // which extensions are shaders (default: FormatTable::defaults())
  std::set<std::string> select;          // empty: every rule
  std::set<std::string> ignore;
  std::map<std::string, Severity> severity;  // per-rule overrides
  nlohmann::json world_sources = nlohmann::json::array();  // the project's extra sources
  const FileSummary* includes = nullptr;  // what the file's #includes declare
  // One of the engine's own shaders (project/includes.h engine_file): its definitions of engine
  // functions are the engine's, with the engine's contracts.
  bool engine_file = false;
  // When set, filled with what the file tells the files that include it (include_summary of its
  // first parse): a lint target's parse serves as its include summary too.
  std::optional<FileSummary>* summary_for_includers = nullptr;
  MacroTable macros;                      // the project's macros (.lwcport.json "macros")
  bool lint_library = false;              // report in the LWC libraries' own definitions too
  bool host_rebases = false;              // the host uploads world data relative to a render origin
  std::optional<UnrealEra> unreal;        // the engine the project builds against (else inferred per file)
  size_t max_bytes = 16u << 20;          // larger files are skipped with a diagnostic
  double max_parse_seconds = 30;         // the parser's budget per file variant (.lwcport.json "max-parse-seconds")
  ParseReuse* reuse = nullptr;           // the document's last parse, for an editor (lang/syntax.h); the result is the same
  ModelReuse* model_reuse = nullptr;     // ... and its last models (world/model.h), which need `reuse`; the same again
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
const WorldData& world_data(Lang lang, const nlohmann::json& extra_sources, bool host_rebases = false);
// How the world model reads a file: in Unreal code, the engine era its own code is written for
// (inferred once from its text). Naming conventions count as evidence in plain code and in
// Unreal code written for UE4 (whatever engine it now builds against): UE5-era code says what is
// large through the engine's large-world types.
ModelContext model_context(const Source& source, Lang lang, const FileSummary* includes, bool engine_file = false);
// What a file's code is written for: "UE4", "UE 5.0-5.3" or "UE 5.4+" for Unreal code (inferred
// from the code, whatever engine the project builds against), else "HLSL" or "GLSL"; "" when
// it is not a shader lwcport knows.
std::string file_era(const Source& source, const AnalyzeOptions& options);

// The macros a file is read with: the built-in table, then what its includes define, then the
// project's (each later one wins).
MacroTable macro_table(Lang lang, const MacroTable* included, const MacroTable& project);
// What a file tells the files that include it: its world model's summary (read without its own
// includes, so no include cycle can change it) and what its #defines teach. `tree` is its
// first variant, parsed with macro_table(..); `context` is model_context(source, lang, nullptr).
FileSummary include_summary(const Source& source, const SyntaxTree& tree, const nlohmann::json& world_sources, bool host_rebases,
                            const ModelContext& context);

// The rule ids a `lwcport-ignore:` comment lists from `from` (just after the colon): each id's
// span in `text`; blanks and commas separate them and anything else ends the list. The parser of
// suppressions and `lint --add-suppressions` read the list the same way.
std::vector<Span> suppression_ids(std::string_view text, size_t from);
// The word every suppression comment holds (`// lwcport-ignore...`): a comment without it suppresses nothing.
constexpr std::string_view kSuppressionMarker = "lwcport-ignore";
// The `lwcport-ignore` comments among a file's comments applied to its findings from another
// front end (lwcport host): suppressed ones dropped, unused suppressions reported (when `ran`
// says lwc-unused-suppression, and the rule a suppression names, ran on the file).
void apply_suppressions(const Source& source, const std::vector<Span>& comments, const std::function<bool(const RuleInfo&)>& ran,
                        std::vector<Finding>& findings);
bool suppression_id_char(char c);

// The paths a file #includes, in order, as written (a scan of its directive lines).
std::vector<std::string> include_paths(std::string_view text);

// The value at a byte offset, as the world model reads it: its span, its kind, and a Markdown
// description (the kind in words, then where it came from, step by step). None where the model
// classified nothing (a keyword, a comment, a value of unknown space).
struct ValueDescription {
  Span span;
  Kind kind;
  std::string markdown;
};
std::optional<ValueDescription> describe_value(const Source& source, const AnalyzeOptions& options, uint32_t offset);

// One syntax error: text the parser could not read (an outermost ERROR node) or a token it had to
// assume (a MISSING one). `lwcport parse` lists these and lint's lwc-input note counts them, both
// through add_syntax_errors.
struct SyntaxError {
  uint32_t offset = 0;
  std::string what;  // "cannot parse this", "missing `}`" (syntax_errors: or why the parser gave up)
  auto operator<=>(const SyntaxError&) const = default;
};
// Adds the errors of one parsed variant; an error the variants share (outside their groups) is one.
void add_syntax_errors(const SyntaxTree& tree, std::set<SyntaxError>& errors);
// The syntax errors of a file, parsed as analyze() parses it (each unit and variant, with
// macro_table's macros: the built-in ones, its includes' and the project's).
std::set<SyntaxError> syntax_errors(const Source& source, const AnalyzeOptions& options);

// An lwc-input finding: a problem with the file itself rather than its code.
Finding input_finding(Severity severity, uint32_t offset, std::string message, std::string hint);
Finding too_large_finding(size_t bytes, size_t limit);

}  // namespace lwc
