#pragma once
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "lang/macros.h"
#include "lang/syntax.h"
#include "world/era.h"
#include "world/pattern.h"

namespace lwc {

namespace analysis {
class Analyzer;  // world/analyzer.h: fills a WorldModel
}  // namespace analysis

// What a value is, as far as large coordinates go.
enum class Kind : uint8_t {
  unknown,
  local,                   // small: object-local, clip, a scalar such as a distance
  direction,               // a vector with no position: normal, axis, difference of positions
  translated,              // translated-world (camera-relative) position
  absolute,                // absolute-world position
  camera_offset,           // PreViewTranslation: minus the camera's absolute position
  world_matrix,            // local (or screen/clip) -> absolute world, translation included
  translated_world_matrix, // local -> translated world
  from_world_matrix,       // absolute world -> view/clip/local
  from_translated_matrix,  // translated world -> view/clip/local
  rotation_matrix,         // 3x3 part: directions only
  local_matrix,            // small -> small (projection, model-view computed on the host)
};
std::string_view kind_name(Kind kind);
std::optional<Kind> parse_kind(std::string_view name);
// Kinds whose float32 form loses precision far from the origin.
bool holds_absolute(Kind kind);
bool is_matrix(Kind kind);
// A name that says it is a point (`LodOrigin`, `VolumeCenter`, `TouchPosition`): where nothing else
// tells, a vector so named taken from a point is a point too, not an offset.
bool named_as_point(std::string_view name);
// A field that is a swizzle: one to four of xyzw, or of rgba.
bool is_swizzle(std::string_view field);

enum class FunctionRole { transform, transform_point, direction, local, join, invert, same, world_value, add, subtract, translated };

// World-space knowledge for one language: rules/world-space.json plus the project's additions.
struct WorldData {
  struct Source {
    PathPattern pattern;
    Kind kind;
    bool by_name = false;  // a naming convention of plain code, not engine data
    bool plain_only = false;  // ... of plain HLSL and GLSL only, never of Unreal code
  };
  struct Function {
    PathPattern pattern;
    FunctionRole role;
  };
  // Absolute view members and functions with a translated-world twin (`View.WorldCameraOrigin` ->
  // `TranslatedWorldCameraOrigin`, `GetWorldPosition` -> `GetTranslatedWorldPosition`).
  struct Twins {
    std::vector<std::string> objects;  // the view objects whose members have twins
    std::map<std::string, std::string> members, functions;
    // From UE 5.0: engine global or struct type -> member -> its translated twin; engine globals.
    std::map<std::string, std::map<std::string, std::string>> engine_members;
    std::map<std::string, std::string> engine_globals;
    // Engine struct type -> member -> its translated twin, both there in every era.
    std::map<std::string, std::map<std::string, std::string>> struct_members;
  };
  std::vector<std::string> float_types;
  std::vector<Source> sources;
  std::vector<Function> functions;
  Twins twins;
  // The LWC libraries' own names: a definition under one of them is the library, not debt.
  struct Library {
    std::vector<std::string> functions, types, still_checked;
  } library;
  UnrealApi unreal_api;  // which engine era defines each large-world name
  // Unreal's structs and functions by era (rules/world-space.json "engine").
  struct EngineMember {
    Kind kind;
    std::array<std::string, 3> types;  // declared in UE4, UE 5.0-5.3, UE 5.4+
    std::optional<Kind> ue5_kind;      // its kind from UE 5.0 on, where it changed
  };
  std::map<std::string, std::map<std::string, EngineMember>> engine_structs;
  std::map<std::string, std::array<Kind, 3>> engine_functions;  // return kind per era
  std::map<std::string, std::array<std::string, 3>> engine_function_types;  // return type per era (UE4, 5.0-5.3, 5.4+)
  std::map<std::string, std::string> engine_objects;  // engine global or call (`Name(..)`) -> its struct
  // An engine function's position parameter that UE5 takes in translated world (UE4: absolute).
  struct TranslatedParameter {
    std::vector<size_t> indices;  // the position parameters it takes in translated world
    UnrealEra from;  // the first era that takes it so
  };
  std::map<std::string, TranslatedParameter> engine_translated_parameters;
  // View members UE5 hands over in translated world under their UE4 name (a plane or a position).
  struct TranslatedInPlace {
    bool plane;
    UnrealEra from;
  };
  std::map<std::string, TranslatedInPlace> view_translated_in_place;
  std::array<std::string, 2> uniform_buffer;  // UE4's primitive uniform buffer, and the call UE5 reads it through
  const EngineMember* engine_member(std::string_view owner, std::string_view member) const;

  // What a place's name says it holds (rules/world-space.json "holder-names").
  struct HolderNames {
    std::vector<std::string> translated, local;
  } holder_names;

  // `world_space` is the "world-space" object; `extra_sources` is the config's list of
  // {"match", "kind", "languages"?}. Throws std::runtime_error naming a bad entry.
  // `host_rebases`: the host uploads world data relative to a render origin, so what the built-in
  // sources name by convention is relative too (the project's own sources keep their kinds).
  static WorldData load(const nlohmann::json& world_space, const nlohmann::json& extra_sources, Lang lang, bool host_rebases = false);
  bool is_float_type(std::string_view type) const;
  // A float matrix type: `float4x4`, `half3x3`, `mat4`.
  bool is_matrix_type(std::string_view type) const;
  // The kind a value has once held by a place of this name: a translated name makes an absolute
  // value translated, a local, relative or clip-space name makes a position small.
  Kind named_kind(std::string_view name, Kind kind) const;
};

// A name the model tracks: a local, parameter, global (uniform, varying...) or struct field.
struct Variable {
  enum class Role { local, parameter, global, field };
  std::string name;
  std::string type;
  Role role = Role::local;
  int decl = -1;          // the declarator's identifier node
  int declaration = -1;   // the whole declaration / parameter / field node
  int function = -1;      // enclosing function_definition, -1 outside functions
  int init = -1;          // initialiser expression, if any
  int block = -1;         // cbuffer / uniform block node for globals declared in one
  bool precise = false;
  bool uniform = false;
  bool output = false;    // an `out`/`inout` parameter
  bool private_global = false;  // a global only this invocation sees (GLSL without a storage qualifier, HLSL static)
  bool clip = false;      // declared with an SV_Position semantic: clip space
  std::string owner;      // for fields: the struct's name
  Kind kind = Kind::unknown;  // for uniforms: from the sources; otherwise the most absolute kind held
  bool operator==(const Variable&) const = default;
};

// A float-typed place found holding absolute-world data.
struct AbsoluteHolder {
  enum class What { variable, field, parameter, return_value };
  What what;
  int site;           // node to report at
  std::string name;
  std::string type;
  Kind kind;
};

// What a function does with one parameter, for callers in files that include it.
struct ParameterUse {
  bool matters = false;  // some use lets its float32 rounding reach a result
  bool harmless = false;  // every use keeps only a direction or a rotation
  std::string type;       // its declared type where every overload of that arity agrees, else ""
  bool engine = false;    // defined in the engine's own shaders (under an /Engine/ virtual root)
  bool translated = false;  // named as translated (`TranslatedWorldPosition`) in every overload
};

// What an included file teaches: its globals' kinds and its functions' return kinds.
struct FileSummary {
  std::map<std::string, Kind> globals;
  std::map<std::string, Kind> function_returns;
  std::map<std::string, std::string> function_return_types;
  MacroTable macros;  // what its #define lines teach about macros used as syntax
  std::map<std::string, std::string> field_types;  // "Struct.Field" -> declared type
  // "name/arity" -> its parameters' uses (over every overload of that arity).
  std::map<std::string, std::vector<ParameterUse>> parameter_uses;
  // "name/arity" -> its difference group (WorldModel::difference_group), from its first definition.
  std::map<std::string, std::vector<size_t>> difference_groups;
  // A function's first definition -> its parameters' kinds, as the model reads them from the
  // declaration (types, names where they count): what verify fills each argument with.
  std::map<std::string, std::vector<Kind>> parameter_kinds;

  // Adds what `from` knows; what this summary already knows wins. `engine`: `from` is a file of
  // the engine's own shaders, whose functions' parameters are marked so.
  void merge(const FileSummary& from, bool engine = false);
};

// What the last models of one document did, function by function, kept so that the model of its
// edited text replays each top-level function's analysis whose inputs the edit left as they were
// (the function's own nodes and those of the functions it reached, and every part of the model's
// state it read) rather than running it again: only what the edit can change is analysed again.
// The result is the model a fresh analysis gives. One per document, for an editor's open ones.
class ModelReuse {
 public:
  ModelReuse();
  ModelReuse(const ModelReuse&) = delete;
  ModelReuse& operator=(const ModelReuse&) = delete;
  ~ModelReuse();
  struct Log;

 private:
  friend class analysis::Analyzer;
  std::map<int, std::unique_ptr<Log>> logs_;  // by variant
};

// What the model knows of a file besides its text.
struct ModelContext {
  const FileSummary* includes = nullptr;  // what its #includes declare
  // Naming-convention sources count beyond the file's own globals (plain and UE4-era code; see
  // rules/world-space.json "by-name").
  bool names_as_evidence = true;
  // Sources marked "by-name": "plain" count (code that is not Unreal's).
  bool plain_names = true;
  // Unreal code: the engine era its own code is written for (rules/world-space.json "engine").
  std::optional<UnrealEra> era;
  // One of the engine's own shaders: its definitions of engine functions keep the engine's
  // contracts (a UE4 lighting function's `WorldPosition` holds an absolute point).
  bool engine_file = false;
  // The document's last models (of trees this tree's parse edited), and this tree's variant.
  ModelReuse* reuse = nullptr;
  int variant = 0;
};

// Classifies every value of one parsed file. Function parameters and returns are followed within
// the file through summaries computed at call sites (memoised per argument kinds): one pass per
// function, no whole-tree fixpoint.
class WorldModel {
 public:
  WorldModel(const SyntaxTree& tree, const WorldData& data, const ModelContext& context = {});
  ~WorldModel();

  // The kind recorded for an expression node (joined over every analysis of its function).
  Kind kind(int node) const;
  // A node's path (`View.WorldCameraOrigin`, `GetPrimitiveData(..).LocalToWorld`), if it has one.
  std::optional<Path> path(int node) const;
  const std::vector<Variable>& variables() const { return variables_; }
  // The variable an identifier refers to, or -1.
  int variable_at(int identifier) const;
  // Identifier nodes that refer to a variable (its declaration excluded).
  std::vector<int> uses(int variable) const;
  // The variable a declarator's identifier declares, or -1.
  int variable_declared_at(int identifier) const;
  // Every global of that name (one per #if arm that declares it).
  const std::vector<int>& globals_named(const std::string& name) const;
  const std::vector<AbsoluteHolder>& absolute_holders() const { return holders_; }
  // Every use of a variable keeps only what float32 holds well far from the origin: a matrix's
  // rotation (a 3x3 cast, a basis row or column, a copy whose translation is then cleared), or a
  // position's direction (normalize, here or in a function of the file it is passed to).
  bool only_harmless_uses(int var, int depth = 0) const;
  // The point parameters (float3/float4) of function `fn` (its definition node) that it uses only
  // in differences with one another, each moved at most by offsets that are no points (`Center +
  // Extent - Point`): passing every one of them translated by the same amount leaves what the
  // function computes as it was. Their indices, in order; empty where fewer than two qualify.
  std::vector<size_t> difference_group(int fn) const;
  // Some use of a variable (or of a copy, or of the parameter of a function of this file it is
  // passed to) lets its float32 rounding reach a result: a difference with a position, a point
  // it transforms, its translation read. Without one there is no evidence of a hazard.
  bool used_where_precision_matters(int var, int depth = 0) const;
  // Some use adds it to or subtracts it from a translated-world position: whatever its name
  // says, the code treats it as translated.
  bool combined_with_translated(int var) const;
  // Nodes whose analysis was cut because they nest too deeply.
  const std::vector<int>& too_deep() const { return too_deep_; }
  // The functions analysed (their definitions), and how many were replayed from the document's
  // last model instead (ModelReuse).
  const std::vector<int>& analysed_functions() const { return analysed_functions_; }
  int replayed_functions() const { return replayed_functions_; }
  FileSummary summary() const;
  // The declared return type of a function of this file, or "".
  std::string function_return_type(const std::string& name) const;
  const SyntaxTree& tree() const { return tree_; }
  const FileSummary* includes() const { return includes_; }
  // How an included function uses the parameter a call passes `argument` to, if known.
  std::optional<ParameterUse> included_parameter_use(int call, int argument) const;
  // How the model read naming conventions in this file (ModelContext).
  bool names_as_evidence() const { return names_as_evidence_; }
  // Unreal code: the engine era its own code is written for (ModelContext::era).
  std::optional<UnrealEra> code_era() const { return era_; }
  bool plain_names() const { return plain_names_; }
  const WorldData& data() const { return data_; }

 private:
  friend class analysis::Analyzer;
  const SyntaxTree& tree_;
  const WorldData& data_;
  std::vector<Variable> variables_;
  // By node id (dense, as large as the tree: a keystroke builds a model of a 5,000-line file, and
  // hash maps of its nodes were a tenth of that): -1 or Kind::unknown where there is nothing.
  std::vector<int> refs_;         // identifier node -> variable
  std::vector<int> declared_at_;  // declarator identifier -> variable
  std::unordered_map<std::string, std::vector<int>> globals_by_name_;  // filled once the analysis is done
  mutable std::vector<std::vector<int>> uses_;  // variable -> its identifier nodes, built on first use
  std::vector<Kind> kinds_;
  std::vector<AbsoluteHolder> holders_;
  std::vector<int> too_deep_;
  std::map<std::string, Kind> returns_;
  std::map<std::string, std::string> return_types_;
  bool names_as_evidence_ = true;
  bool plain_names_ = true;
  std::optional<UnrealEra> era_;
  std::set<int> cleared_;  // matrices whose translation the code clears (M[3] = ...)
  std::vector<int> analysed_functions_;
  int replayed_functions_ = 0;

  const FileSummary* includes_ = nullptr;  // valid while the model is: the caller's summary
  // "name/arity" -> each overload's parameter variables in order (-1 where unnamed), built on first use.
  mutable std::map<std::string, std::vector<std::vector<int>>> parameters_by_function_;
  // used_where_precision_matters of the globals asked so far: the same for every declaration of a
  // name with the same shape (a matrix or not, an array or not), at the same depth.
  mutable std::map<std::tuple<std::string, bool, bool, int>, bool> global_precision_;

  // used_where_precision_matters, worked out from the variable's uses.
  bool precision_matters(int var, int depth) const;

  bool parameter_only_normalised(int call, int argument, int depth) const;
  // `vec4(v, 0.0)` / `float4(v, 0)`: a direction, which a matrix only rotates.
  bool is_direction_vector(int node) const;
  // The other operand a matrix meets in `M * x`, `x * M` or `mul(x, M)`, or -1.
  int transformed_operand(int matrix_use) const;
  std::vector<int> parameters_receiving(int call, int argument) const;
};

// Where a file defines the LWC libraries themselves (rules/world-space.json "library-definitions"):
// each function or type defined under a library name, or the whole file when (nearly: four in
// five of at least five) every function it defines is one.
std::vector<Span> library_definitions(const SyntaxTree& tree, const WorldData& data);

// Words written before a declaration's type: qualifiers and modifiers (`static const`,
// `uniform`, `precise`, `out`...), read from the original text so HLSL's masked words count.
std::vector<std::string_view> leading_words(const SyntaxTree& tree, int declaration);

}  // namespace lwc
