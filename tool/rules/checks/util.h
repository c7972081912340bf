#pragma once
#include <initializer_list>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/finding.h"
#include "rules/rule.h"
#include "world/pattern.h"

namespace lwc::checks {

// Every node of a type, in source order.
const std::vector<int>& nodes_of(const SyntaxTree& tree, std::string_view type);
// Every node of any of these types, in source order.
std::vector<int> nodes_of(const SyntaxTree& tree, std::initializer_list<std::string_view> types);
// The called name of a call_expression when it is a plain identifier, else "".
std::string_view call_name(const SyntaxTree& tree, int call);
std::vector<int> call_arguments(const SyntaxTree& tree, int call);
// A rule-data list of strings (globs allowed) and a match against it.
std::vector<std::string> string_list(const nlohmann::json& data, const char* key);
bool matches_any(const std::vector<std::string>& globs, std::string_view text);
// The name of a function definition when it is a plain identifier, or -1.
int function_name(const SyntaxTree& tree, int definition);
// An engine member as UE5 spells it: UE4's primitive uniform buffer (`Primitive.X`, when the file
// does not declare that name itself) is read through a call in UE5
// (`GetPrimitiveDataFromUniformBuffer().X`, rules/world-space.json engine "uniform-buffer");
// anything else as written.
std::string ue5_spelling(const CheckContext& ctx, int node);
// The file defines a function of that name itself (its own copy, as plugins carry): not the engine's.
bool defines_function(const SyntaxTree& tree, std::string_view name);
// The one definition of a function of this file called `name` (-1 when none, or overloads); with
// `arity`, the one taking that many parameters.
int defined_function(const SyntaxTree& tree, std::string_view name);
int defined_function(const SyntaxTree& tree, std::string_view name, size_t arity);
// The number of parameters a function definition declares.
size_t function_arity(const SyntaxTree& tree, int definition);
// The model's variable for the `index`-th parameter of a function definition, or -1.
int parameter_variable(const CheckContext& ctx, int definition, size_t index);
// True when `node` is `base.name`: that member or swizzle of that expression.
bool is_field_of(const SyntaxTree& tree, int node, int base, std::string_view name);
// A 3-vector's own value: the node without its trailing `.xyz` (`View.PreViewTranslation.xyz`).
int without_xyz(const SyntaxTree& tree, int node);
// True when `node` is read one or two coordinates at a time (`P.z`, `P.xy`): a height, a clamp,
// where the absolute value is what the code wants.
bool read_as_coordinates(const SyntaxTree& tree, int node);
// True when an identifier is the name being declared or defined (a macro, a function), not a use.
bool is_definition_name(const SyntaxTree& tree, int identifier);

// `Object.Member` (or `Call(..).Member`) split; empty when the node is anything else.
struct Member {
  std::string object, member;
  bool empty() const { return member.empty(); }
};
Member member_of(const SyntaxTree& tree, int node);
// The engine struct a member access (`X.M`) reads: a variable's declared type, or the struct of an
// engine global or call (rules/world-space.json engine "objects") the file does not declare; "".
std::string engine_struct_of(const CheckContext& ctx, int field);
// The entry of the engine's struct table a member access reads (`Primitive.LocalToWorld`), or null.
const WorldData::EngineMember* engine_member_at(const CheckContext& ctx, int node);
// The translated-world twin of an absolute view member or function call, as text
// (`View.WorldCameraOrigin` -> `PrimaryView.TranslatedWorldCameraOrigin`,
// `GetWorldPosition(P)` -> `GetTranslatedWorldPosition(P)`), or "" when it has none.
std::string translated_twin(const CheckContext& ctx, int node);
// A view member UE5 hands over in translated world under its UE4 name (rules/world-space.json
// engine "view-members-translated-in-place"), read by UE4 code that moves to an era where it is
// so; else null.
const WorldData::TranslatedInPlace* view_member_translated_in_place(const CheckContext& ctx, int node);
// A value that UE4 code builds from such a member's position (directly, or through locals): in
// the target era it is a translated point already, as the engine's functions there take it.
bool translated_in_target(const CheckContext& ctx, int node, int depth = 0);
// An engine member or global that UE 5.0 replaced by its translated-world twin (a light's
// position, a shadow matrix), read under its UE4 name: the twin as text
// (`DeferredLightUniforms.TranslatedWorldPosition`), or "". translated_twin() offers these only in
// code built against UE 5.0 or later, where the twins exist.
std::string engine_translated_twin(const CheckContext& ctx, int node);

// An argument a function takes in translated world: an engine function that takes it so where UE4
// took absolute world (rules/world-space.json engine "translated-parameters"), in the era the code
// moves to (UE4 code: UE 5.4), `from` getting the first era that does; else one whose own
// declaration (in this file or an included one) names the parameter as translated (`declared`
// set). The call, or -1. A function the file or the project's own headers define takes what its
// declaration says, so it is never the engine's.
int translated_parameter_call(const CheckContext& ctx, int argument, UnrealEra* from = nullptr, bool* declared = nullptr);

// A world-position rewrite of one variable: its edits, or why it is withheld.
struct RewritePlan {
  std::vector<Edit> edits;
  std::string blocker;                // non-empty: the rewrite is withheld, and this says why
  std::vector<std::string> helpers;   // functions of a header that now take translated positions
  std::vector<std::string> notes;     // what must change outside the shader
  std::vector<std::string> library;   // shader-library names the new code calls
  std::vector<std::string> interface; // stage inputs/outputs renamed: the other stage must follow
  std::vector<int> moving_functions;  // functions whose return becomes translated in this plan
  std::vector<int> moving_variables;  // locals that become translated in this plan
  size_t followed = 0;  // uses that took the translated value as it is
  size_t bridged = 0;   // uses that need the absolute value, recovered from the translated one
};
RewritePlan withheld(std::string why);
// A plan's size at one moment, to try a step on the plan itself and take it back if it fails:
// every step only appends (or rewrites what it appended), so the plan up to the mark is kept. A
// copy of the plan per try costs its whole size, and a chain tries once per caller.
struct PlanMark {
  size_t edits, helpers, notes, library, interface, functions, variables, followed, bridged;
  std::string blocker;
};
PlanMark mark(const RewritePlan& plan);
void roll_back(RewritePlan& plan, const PlanMark& mark);

// The camera-relative name of a world-position name: WorldPos -> TranslatedWorldPos,
// vWorldPosition -> vTranslatedWorldPosition, AbsoluteWorldPosition -> TranslatedWorldPosition.
std::string translated_name(const std::string& name);
// The mul(A, M) call a node is, looking through a trailing swizzle (`mul(..).xyz`), or -1.
int mul_call(const SyntaxTree& tree, int node);
// The position of a `float4(P, 1)` / `vec4(P, 1.0)` / `float4(x, y, z, 1)` call as text, or "".
std::string position_of_homogeneous(const SyntaxTree& tree, int node);
// The direction of a `float4(D, 0)` / `vec4(x, y, z, 0.0)` call as text, or "".
std::string direction_of_homogeneous(const SyntaxTree& tree, int node);
// The `float4(use, 1)` / `vec4(use, 1.0)` call that wraps a use, or -1.
int homogeneous_wrapper(const SyntaxTree& tree, int use);
// The names of a model's variables by where they are declared: in a function (locals and
// parameters) or outside every function (globals, fields). Built once per run of a check.
class DeclaredNames {
 public:
  explicit DeclaredNames(const WorldModel& world);
  // True when a new variable called `name` in `function` (-1: file scope) would clash with one in
  // the same function or at file scope.
  bool taken(std::string_view name, int function) const;

 private:
  std::set<std::pair<std::string_view, int>> names_;  // name, function (-1 outside functions)
};
// The other operand of `use - X` / `X - use` (looking through parentheses), or -1.
int subtraction_partner(const SyntaxTree& tree, int use);
// Why a use of a world position cannot be followed, for the withheld message.
std::string escape(const SyntaxTree& tree, int use);
int line_of(const SyntaxTree& tree, int node);
// The value under a demotion to float (`DFDemote(M)`, `DFHackToFloat(M)`, `LWCToFloat(M)`, through
// parentheses), or the node itself.
int undemoted(const SyntaxTree& tree, int node);
// True for an expression statement of a function's own body, run whenever the function runs (not
// under a branch or a loop).
bool unconditional_statement(const SyntaxTree& tree, int statement);
// A node's span, widened to its whole lines (indentation and line end) when nothing else shares
// them: the span that deletes a statement without leaving a blank line.
Span whole_lines(const SyntaxTree& tree, int node);
// The `#version` directive of a GLSL file, or -1.
int version_directive(const SyntaxTree& tree);
// The GLSL version written (e.g. "300 es"; "110" when there is no #version) when it has no
// `precise` (before 4.00, or ES 3.20), else "".
std::string glsl_version_without_precise(const SyntaxTree& tree);

}  // namespace lwc::checks
