#pragma once
// The world-space analysis of one file, inside world/: the Analyzer that fills a WorldModel,
// its kind algebra and what it logs for ModelReuse. Its parts: model.cpp (the run, declarations
// and functions), expressions.cpp (what an expression holds), replay.cpp (a document's last
// model replayed).
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "world/model.h"

namespace lwc {
namespace analysis {

// How strongly a kind calls for attention when two flows meet.
int rank(Kind k);
Kind join(Kind a, Kind b);
bool small(Kind k);
Kind add(Kind a, Kind b);
Kind subtract(Kind a, Kind b);
// Component-wise multiply or divide by a non-matrix.
Kind scale(Kind a, Kind b);
Kind negate(Kind k);
Kind invert(Kind k);
// Apply `first`, then `second`.
Kind compose(Kind first, Kind second);
bool ends_with(std::string_view s, std::string_view suffix);
// float3x3, half3x3, mat3, mat3x3, matrix<float,3,3>.
bool is_3x3_type(std::string_view t);
constexpr int kMaxDepth = 400;

bool has_word(const std::vector<std::string_view>& words, std::string_view w);
Variable make_variable(std::string name, std::string type, Variable::Role role, int decl, int declaration, int function = -1);

struct Summary {
  Kind ret = Kind::unknown;
  std::vector<Kind> outs;
  bool operator==(const Summary&) const = default;
};
using MemoKey = std::pair<int, std::vector<Kind>>;  // a function definition, the kinds of its arguments

// What the file stores into a GLSL stage output named as world-space data.
struct NamedOutput {
  bool stored = false, unclassified = false;
  Kind stored_kind = Kind::unknown;  // joined over the stores
  bool operator==(const NamedOutput&) const = default;
};

// A variable's part of the model's state, as a function's analysis reads and leaves it.
struct VariableState {
  Kind kind = Kind::unknown;
  std::optional<NamedOutput> output;
  bool operator==(const VariableState&) const = default;
};

// One top-level function's analysis (with every analysis of a callee it started): the state it
// read or changed, as it was before (first touch; nullopt: not there yet) and after, and what it
// added to the model. Node ids are those of the tree it ran on; variables are named by their
// declarator node.
struct RunLog {
  std::vector<int> functions;  // function definitions whose nodes it read
  std::vector<Variable> created;
  std::vector<std::pair<int, std::optional<VariableState>>> variables_before;
  std::vector<std::pair<int, VariableState>> variables_after;
  std::vector<std::pair<MemoKey, std::optional<Summary>>> memo_before;
  std::vector<std::pair<MemoKey, Summary>> memo_after;
  std::vector<std::pair<std::string, std::optional<Kind>>> fields_before;
  std::vector<std::pair<std::string, Kind>> fields_after;
  std::vector<std::pair<int, Kind>> kinds;  // node -> what the analysis recorded, joined
  std::vector<std::pair<int, int>> refs;    // identifier -> the declarator of its variable
  std::vector<AbsoluteHolder> reports;      // in order
  std::vector<int> too_deep, cleared;       // nodes; declarators
  std::vector<std::pair<std::string, Kind>> returns;
  std::vector<std::pair<std::string, std::string>> return_types;
};

}  // namespace analysis

struct ModelReuse::Log {
  uint64_t tree = 0;  // SyntaxTree::number of the tree the model ran on
  const WorldData* data = nullptr;
  const FileSummary* includes = nullptr;
  bool names_as_evidence = true, plain_names = true;
  std::optional<UnrealEra> era;
  std::vector<Variable> collected;  // the variables the declarations outside functions made
  std::vector<int> function_order;
  std::vector<std::string> function_names;  // in that order
  std::unordered_map<int, analysis::RunLog> runs;  // by function definition
};

namespace analysis {

// The analysis itself; WorldModel keeps only its results.
class Analyzer {
 public:
  Analyzer(WorldModel& m, const ModelContext& context) : m_(m), t_(m.tree_), d_(m.data_), inc_(context.includes), context_(context) {}

  void run();

 private:
  struct Frame {
    int function = -1;
    std::unordered_map<std::string, int> scope;  // name -> variable
    std::unordered_map<int, Kind> current;       // variable -> kind now
    Kind ret = Kind::unknown;
  };

  // ---- declarations -------------------------------------------------------------------------
  std::string_view type_of(int declaration) const;

  int declarator_name(int d) const { return t_.declarator_name(d); }

  // A declaration whose HLSL semantic is SV_Position (masked out of the tree, read from the file):
  // the value is in clip space, whatever its name says.
  bool clip_semantic(int declaration) const;

  int new_variable(Variable v);

  std::string function_name(int fn) const;

  void collect();
  // UE4 code: a parameter passed whole to an engine function that takes a world position (one UE5
  // moved to translated world) holds an absolute position by UE4's contract.
  void engine_contract_parameters();
  // What the structure of the code says (contracts.cpp): a point added to the pre-view translation is
  // absolute, and so is a uniform point taken from an absolute one.
  void absolute_by_translation();

  void collect_struct(int id);

  void collect_global(int id);
  // The file is the body of a material custom node (a `return` outside every function): its
  // file-level declarations are the node function's locals, not uniforms.
  bool custom_node_body() const;

  bool private_storage(const std::vector<std::string_view>& words) const;

  // `name_counts`: a naming convention may say what it holds.
  int add_global(int declaration, int name, std::string type, int block, bool uniform, bool precise, bool output = false,
                 bool name_counts = true);

  // ---- functions ----------------------------------------------------------------------------
  Summary analyze_function(int fn, const std::vector<Kind>& args);

  // Statements in order, without recursion: nesting depth is the file's, not the stack's.
  void walk(int body);

  bool is_expression(int id) const;

  void declare_locals(int id);

  void note_return(Kind k);

  Kind current(int var) const;

  // `var` now holds `k`: remember it, and report a float-typed holder of absolute data.
  void hold(int var, Kind k, int site);

  void report(AbsoluteHolder h);

  // ---- expressions --------------------------------------------------------------------------
  // The kind a source pattern gives a path. Naming conventions ("by-name") count for a global
  // the file declares (a uniform is named for what the host puts in it), and elsewhere only where
  // names are evidence (plain and UE4-era code).
  std::optional<Kind> source_kind(const Path& path, bool declared_global = false);

  std::optional<FunctionRole> role_of(std::string_view name) const;

  int lookup(std::string_view name) const;

  static void join_at(std::unordered_map<int, Kind>& kinds, int id, Kind k);
  // The same on the model's kinds by node, where nothing recorded is Kind::unknown (its join with
  // any kind is that kind).
  void join_at_node(int id, Kind k);

  Kind record(int id, Kind k);

  void refer(int identifier, int var);

  Kind eval(int id, int depth);

  Kind eval_node(int id, int depth);

  Kind eval_identifier(int id);

  Kind eval_field(int id, int depth);

  // 0, 1, 2 for UE4, UE 5.0-5.3, UE 5.4+ (the engine tables' columns); -1 outside Unreal code.
  int era_column() const;

  // The struct type of a field access's base, when the base is a known variable.
  std::string owner_of(int base) const;

  // A struct field's declared type: in this file, else in an include; "" when unknown (an
  // unknown owner matches a field name that only one struct declares).
  std::string field_type(const std::string& owner, const std::string& name) const;

  Kind eval_subscript(int id, int depth);

  // An operand whose type is a matrix (`float4x4`, `mat4`, a matrix-typed variable or field).
  bool matrix_typed(int n) const;
  // Declared as a large-world type (FDF*, FLWC*): a variable, or a field whose type is known.
  bool large_world_typed(int n) const;

  // A vector that a matrix transforms as a point (w = 1) rather than a direction (w = 0 or no w).
  bool is_point(int v) const;

  // `as_point`: the function treats a 3-vector as a point (DFMultiply(float3, FDFMatrix)).
  Kind transform(int vec, Kind vk, Kind mk, bool as_point = false);

  Kind eval_call(int id, int depth);

  Kind apply_role(FunctionRole role, const std::vector<int>& args, const std::vector<Kind>& k);

  Kind call_user(const std::vector<int>& overloads, const std::vector<int>& args, const std::vector<Kind>& kinds);

  Kind eval_binary(int id, int depth);

  Kind binary(std::string_view op, int l, Kind a, int r, Kind b);

  bool constant(int n) const;

  // An expression whose name (its variable, or its last field) says it is a position.
  bool named_position(int n) const;

  Kind eval_assignment(int id, int depth);

  void assign(int lhs, Kind k);

  // ---- replaying the document's last model (ModelReuse) ------------------------------------
  // This model's log, when the document keeps one; the last model's, when it ran on the tree this
  // tree's parse edited, with the same data and context, and the declarations outside functions
  // made the same variables.
  void prepare_reuse();

  static constexpr int kGone = -2;  // a node of the last tree this tree does not have
  int new_id(int old) const { return old < 0 ? old : static_cast<size_t>(old) < to_new_.size() ? to_new_[old] : kGone; }

  // A variable of the last model as this tree has it (node ids moved).
  Variable moved(Variable v) const;

  VariableState variable_state(int var) const;

  std::optional<Summary> memo_entry(const MemoKey& key) const;

  std::optional<Kind> field_kind(const std::string& key) const;

  // The first time the analysis being recorded reads or changes a part of the state: as it was.
  void touch_variable(int var) const;
  void touch_field(const std::string& key);

  void begin_run();

  void end_run(int fn);

  // The last model's analysis of this function, applied to this one, when everything it read is
  // as it was: the functions it read are unchanged (copied from the last tree) and the state it
  // touched holds what it held then.
  bool replay(int fn);

  WorldModel& m_;
  const SyntaxTree& t_;
  const WorldData& d_;
  const FileSummary* inc_;
  const ModelContext& context_;
  std::unique_ptr<ModelReuse::Log> log_;
  ModelReuse::Log* old_ = nullptr;  // its runs move to log_ as they are replayed
  std::vector<int> to_old_, to_new_;  // node ids between the last tree and this one (kGone: none)
  RunLog current_run_;
  RunLog* run_ = nullptr;  // the top-level analysis being recorded
  mutable std::unordered_map<int, std::optional<VariableState>> touched_variables_;
  std::set<MemoKey> touched_memo_;
  std::set<std::string> touched_fields_;
  std::unordered_map<int, Kind> run_kinds_;
  Frame* frame_ = nullptr;
  std::unordered_map<std::string, std::vector<int>> functions_;
  std::vector<int> function_order_;
  std::unordered_map<std::string, int> globals_;
  std::unordered_map<std::string, int> fields_;
  std::unordered_map<std::string, std::vector<int>> fields_by_name_;
  std::unordered_map<std::string, Kind> field_kinds_;
  std::set<std::string> block_instances_;
  std::unordered_map<int, int> decl_var_;
  std::map<std::pair<int, std::vector<Kind>>, Summary> memo_;
  std::set<int> active_;
  std::set<int> reported_;
  std::unordered_map<std::string, std::optional<Kind>> source_cache_;
  // GLSL stage outputs named as world-space data, and what the file stores into them.
  std::map<int, NamedOutput> named_outputs_;
  // Included fields by name -> their one type ("" when types differ), built on first use.
  mutable std::optional<std::unordered_map<std::string, std::string>> include_field_by_name_;
  mutable std::optional<bool> custom_node_body_;
};

}  // namespace analysis
}  // namespace lwc
