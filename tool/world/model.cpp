#include "world/model.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <set>
#include <stdexcept>

namespace lwc {

namespace {

constexpr std::pair<Kind, std::string_view> kKindNames[] = {
    {Kind::unknown, "unknown"},
    {Kind::local, "local"},
    {Kind::direction, "direction"},
    {Kind::translated, "translated-position"},
    {Kind::absolute, "absolute-position"},
    {Kind::camera_offset, "camera-offset"},
    {Kind::world_matrix, "world-matrix"},
    {Kind::translated_world_matrix, "translated-world-matrix"},
    {Kind::from_world_matrix, "from-world-matrix"},
    {Kind::from_translated_matrix, "from-translated-matrix"},
    {Kind::rotation_matrix, "rotation-matrix"},
    {Kind::local_matrix, "local-matrix"},
};

constexpr std::pair<FunctionRole, std::string_view> kRoleNames[] = {
    {FunctionRole::transform, "transform"}, {FunctionRole::transform_point, "transform-point"},
    {FunctionRole::direction, "direction"},
    {FunctionRole::local, "local"},         {FunctionRole::join, "join"},
    {FunctionRole::invert, "invert"},       {FunctionRole::same, "same"},
    {FunctionRole::world_value, "world-value"},
    {FunctionRole::add, "add"},             {FunctionRole::subtract, "subtract"},
    {FunctionRole::translated, "translated"},
};

// How strongly a kind calls for attention when two flows meet.
int rank(Kind k) {
  switch (k) {
    case Kind::unknown: return 0;
    case Kind::local: return 1;
    case Kind::direction:
    case Kind::rotation_matrix:
    case Kind::local_matrix: return 2;
    case Kind::translated:
    case Kind::translated_world_matrix:
    case Kind::from_translated_matrix: return 3;
    case Kind::camera_offset:
    case Kind::from_world_matrix: return 4;
    case Kind::absolute:
    case Kind::world_matrix: return 5;
  }
  return 0;
}

Kind join(Kind a, Kind b) { return rank(b) > rank(a) ? b : a; }

bool small(Kind k) { return k == Kind::direction || k == Kind::local || k == Kind::unknown; }

Kind add(Kind a, Kind b) {
  // A camera-relative position plus the camera's absolute position is absolute again.
  if ((a == Kind::translated && b == Kind::absolute) || (a == Kind::absolute && b == Kind::translated)) return Kind::absolute;
  // Adding PreViewTranslation to a position (or to what is most likely one) translates it.
  if ((a == Kind::absolute || a == Kind::unknown) && b == Kind::camera_offset) return Kind::translated;
  if (a == Kind::camera_offset && (b == Kind::absolute || b == Kind::unknown)) return Kind::translated;
  for (auto [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
    if ((x == Kind::absolute || x == Kind::translated || x == Kind::camera_offset) && small(y)) return x;
  }
  if (a == Kind::direction || b == Kind::direction) return (small(a) && small(b)) ? Kind::direction : Kind::unknown;
  if (a == Kind::local && b == Kind::local) return Kind::local;
  return Kind::unknown;
}

Kind subtract(Kind a, Kind b) {
  if (a == b && (a == Kind::absolute || a == Kind::translated)) return Kind::direction;
  if (a == Kind::translated && b == Kind::camera_offset) return Kind::absolute;
  if ((a == Kind::absolute || a == Kind::translated || a == Kind::camera_offset) && small(b)) return a;
  if (a == Kind::direction && (b == Kind::direction || b == Kind::local)) return Kind::direction;
  if (a == Kind::local && b == Kind::local) return Kind::local;
  return Kind::unknown;
}

// Component-wise multiply or divide by a non-matrix.
Kind scale(Kind a, Kind b) {
  if (is_matrix(a) || is_matrix(b)) return Kind::unknown;
  if (holds_absolute(a) || holds_absolute(b)) return join(a, b);
  if (a == Kind::unknown || b == Kind::unknown) return Kind::unknown;
  return join(a, b);
}

Kind negate(Kind k) {
  if (k == Kind::absolute) return Kind::camera_offset;
  if (k == Kind::camera_offset) return Kind::absolute;
  return k;
}

Kind invert(Kind k) {
  switch (k) {
    case Kind::world_matrix: return Kind::from_world_matrix;
    case Kind::from_world_matrix: return Kind::world_matrix;
    case Kind::translated_world_matrix: return Kind::from_translated_matrix;
    case Kind::from_translated_matrix: return Kind::translated_world_matrix;
    case Kind::rotation_matrix:
    case Kind::local_matrix: return k;
    default: return Kind::unknown;
  }
}

// Apply `first`, then `second`.
Kind compose(Kind first, Kind second) {
  if (first == Kind::world_matrix && second == Kind::from_world_matrix) return Kind::local_matrix;
  if (first == Kind::translated_world_matrix && second == Kind::from_translated_matrix) return Kind::local_matrix;
  if ((first == Kind::local_matrix || first == Kind::rotation_matrix) && second != Kind::unknown) return second;
  if ((second == Kind::local_matrix || second == Kind::rotation_matrix) &&
      (first == Kind::from_world_matrix || first == Kind::from_translated_matrix))
    return first;
  return Kind::unknown;
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

// float3x3, half3x3, mat3, mat3x3, matrix<float,3,3>.
bool is_3x3_type(std::string_view t) {
  return ends_with(t, "3x3") || t == "mat3" || (t.find("matrix") == 0 && ends_with(t, "3,3>")) ||
         (t.find("matrix") == 0 && ends_with(t, "3, 3>"));
}

constexpr int kMaxDepth = 400;

}  // namespace

std::string_view kind_name(Kind kind) {
  for (auto [k, n] : kKindNames)
    if (k == kind) return n;
  return "unknown";
}

std::optional<Kind> parse_kind(std::string_view name) {
  for (auto [k, n] : kKindNames)
    if (n == name) return k;
  return std::nullopt;
}

bool holds_absolute(Kind k) {
  return k == Kind::absolute || k == Kind::camera_offset || k == Kind::world_matrix || k == Kind::from_world_matrix;
}

bool is_matrix(Kind k) {
  return k == Kind::world_matrix || k == Kind::translated_world_matrix || k == Kind::from_world_matrix ||
         k == Kind::from_translated_matrix || k == Kind::rotation_matrix || k == Kind::local_matrix;
}

bool is_swizzle(std::string_view f) {
  if (f.empty() || f.size() > 4) return false;
  bool xyzw = f.find_first_not_of("xyzw") == std::string_view::npos;
  bool rgba = f.find_first_not_of("rgba") == std::string_view::npos;
  return xyzw || rgba;
}

static bool applies_to(const nlohmann::json& entry, Lang lang) {
  if (!entry.contains("languages")) return true;
  for (const auto& l : entry.at("languages"))
    if (l.get<std::string>() == lang_name(lang)) return true;
  return false;
}

WorldData WorldData::load(const nlohmann::json& ws, const nlohmann::json& extra_sources, Lang lang) {
  WorldData d;
  for (const auto& t : ws.at("float-types")) d.float_types.push_back(t.get<std::string>());
  auto add_sources = [&](const nlohmann::json& list, std::string_view where) {
    for (const auto& s : list) {
      if (!s.is_object() || !s.contains("match") || !s.contains("kind"))
        throw std::runtime_error(std::string(where) + ": a world source needs \"match\" and \"kind\": " + s.dump());
      auto kind = parse_kind(s.at("kind").get<std::string>());
      if (!kind) throw std::runtime_error(std::string(where) + ": unknown world-space kind " + s.at("kind").dump());
      const nlohmann::json by_name = s.value("by-name", nlohmann::json(false));
      if (!by_name.is_boolean() && by_name != "plain")
        throw std::runtime_error(std::string(where) + ": \"by-name\" is true, false or \"plain\": " + s.dump());
      bool plain_only = by_name == "plain";
      PathPattern pattern(s.at("match").get<std::string>());
      if (std::string why = pattern.problem(); !why.empty())
        throw std::runtime_error(std::string(where) + ": " + s.at("match").dump() + " can match nothing: " + why);
      if (applies_to(s, lang)) d.sources.push_back({pattern, *kind, plain_only || by_name == true, plain_only});
    }
  };
  // The project's sources come first so they can override the built-in ones.
  if (extra_sources.is_array()) add_sources(extra_sources, "world-sources");
  add_sources(ws.at("sources"), "rules/world-space.json");
  for (const auto& f : ws.at("functions")) {
    if (!applies_to(f, lang)) continue;
    std::string role = f.at("role").get<std::string>();
    auto it = std::find_if(std::begin(kRoleNames), std::end(kRoleNames), [&](auto& p) { return p.second == role; });
    if (it == std::end(kRoleNames)) throw std::runtime_error("rules/world-space.json: unknown function role " + role);
    PathPattern pattern(f.at("match").get<std::string>());
    if (std::string why = pattern.problem(); !why.empty())
      throw std::runtime_error("rules/world-space.json: " + f.at("match").dump() + " can match nothing: " + why);
    d.functions.push_back({pattern, it->first});
  }
  const auto& twins = ws.at("translated-twins");
  d.twins.objects = twins.at("objects").get<std::vector<std::string>>();
  d.twins.members = twins.at("members").get<std::map<std::string, std::string>>();
  d.twins.functions = twins.at("functions").get<std::map<std::string, std::string>>();
  const auto& library = ws.at("library-definitions");
  d.library = {library.at("functions").get<std::vector<std::string>>(), library.at("types").get<std::vector<std::string>>(),
               library.at("still-checked").get<std::vector<std::string>>()};
  d.unreal_api = UnrealApi::load(ws.at("unreal-api"));
  auto kind_of = [](const nlohmann::json& j) {
    auto k = parse_kind(j.get<std::string>());
    if (!k) throw std::runtime_error("rules/world-space.json: engine: unknown kind " + j.dump());
    return *k;
  };
  for (const auto& [owner, members] : ws.at("engine").at("structs").items())
    for (const auto& [member, e] : members.items()) {
      EngineMember m{kind_of(e.at(0)), {e.at(1).get<std::string>(), e.at(2).get<std::string>(), e.at(3).get<std::string>()}, {}};
      if (e.size() > 4) m.ue5_kind = kind_of(e.at(4));
      d.engine_structs[owner][member] = m;
    }
  for (const auto& [name, e] : ws.at("engine").at("functions").items())
    d.engine_functions[name] = {kind_of(e.at(0)), kind_of(e.at(1)), kind_of(e.at(2))};
  const auto& names = ws.at("holder-names");
  d.holder_names = {names.at("translated").get<std::vector<std::string>>(), names.at("local").get<std::vector<std::string>>()};
  return d;
}

const WorldData::EngineMember* WorldData::engine_member(std::string_view owner, std::string_view member) const {
  auto s = engine_structs.find(std::string(owner));
  if (s == engine_structs.end()) return nullptr;
  auto m = s->second.find(std::string(member));
  return m == s->second.end() ? nullptr : &m->second;
}

Kind WorldData::named_kind(std::string_view name, Kind k) const {
  auto any = [&](const std::vector<std::string>& globs) {
    return std::any_of(globs.begin(), globs.end(), [&](const std::string& g) { return glob_match(g, name); });
  };
  bool position = k == Kind::absolute || k == Kind::camera_offset;
  if (position && any(holder_names.translated)) return Kind::translated;
  if (k == Kind::world_matrix && any(holder_names.translated)) return Kind::translated_world_matrix;
  if (k == Kind::from_world_matrix && any(holder_names.translated)) return Kind::from_translated_matrix;
  bool world = name.find("World") != std::string_view::npos || name.find("world") != std::string_view::npos;
  if (position && !world && any(holder_names.local)) return Kind::local;
  return k;
}

bool WorldData::is_float_type(std::string_view type) const {
  for (const auto& g : float_types)
    if (glob_match(g, type)) return true;
  return false;
}

std::vector<Span> library_definitions(const SyntaxTree& tree, const WorldData& data) {
  auto any = [](const std::vector<std::string>& globs, std::string_view name) {
    return std::any_of(globs.begin(), globs.end(), [&](const std::string& g) { return glob_match(g, name); });
  };
  std::vector<Span> out;
  size_t functions = 0, library_functions = 0;
  for (int id = 0; id < static_cast<int>(tree.nodes.size()); ++id) {
    std::string_view type = tree.at(id).type;
    if (type == "function_definition") {
      ++functions;
      int name = tree.declarator_name(tree.child_by_field(id, "declarator"));
      if (name >= 0 && any(data.library.functions, tree.text(name))) {
        ++library_functions;
        out.push_back(tree.span(id));
      }
    } else if (type == "struct_specifier" && tree.child_by_field(id, "body") >= 0) {
      int name = tree.child_by_field(id, "name");
      if (name >= 0 && any(data.library.types, tree.text(name))) out.push_back(tree.span(id));
    } else if (type == "type_definition") {
      int name = tree.child_by_field(id, "declarator");
      if (name >= 0 && any(data.library.types, tree.text(name))) out.push_back(tree.span(id));
    }
  }
  // A file that is mostly the library (its few other functions, like LargeWorldCoordinates.ush's
  // WaveReadLaneAt overloads for the FLWC types, serve it) is the library as a whole.
  if (functions > 0 && (library_functions == functions || (functions >= 5 && library_functions * 5 >= functions * 4)))
    return {tree.span(0)};
  return out;
}

std::vector<std::string_view> leading_words(const SyntaxTree& tree, int declaration) {
  std::vector<std::string_view> words;
  int type = tree.child_by_field(declaration, "type");
  // A GLSL interface block has no type: its qualifiers end at its member list.
  if (type < 0)
    for (int c : tree.named_children(declaration))
      if (tree.is(c, "field_declaration_list")) type = c;
  uint32_t begin = tree.at(declaration).begin;
  uint32_t end = type >= 0 ? tree.at(type).begin : begin;
  // HLSL's masked modifiers (`out`, `uniform`...) lie just before the node: take the words
  // before it on the same line, back to the nearest punctuation.
  if (tree.lang == Lang::hlsl) {
    const std::string& src = tree.source->text();
    while (begin > 0) {
      char c = src[begin - 1];
      if (c == '\n' || !(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ' ' || c == '\t')) break;
      --begin;
    }
  }
  std::string_view text = tree.source->slice({begin, end});
  size_t i = 0;
  while (i < text.size()) {
    if (std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_') {
      size_t b = i;
      while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) ++i;
      words.push_back(text.substr(b, i - b));
    } else {
      ++i;
    }
  }
  return words;
}

static bool has_word(const std::vector<std::string_view>& words, std::string_view w) {
  return std::find(words.begin(), words.end(), w) != words.end();
}

static Variable make_variable(std::string name, std::string type, Variable::Role role, int decl, int declaration,
                              int function = -1) {
  Variable v;
  v.name = std::move(name);
  v.type = std::move(type);
  v.role = role;
  v.decl = decl;
  v.declaration = declaration;
  v.function = function;
  return v;
}

namespace {

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

}  // namespace

struct ModelReuse::Log {
  uint64_t tree = 0;  // SyntaxTree::number of the tree the model ran on
  const WorldData* data = nullptr;
  const FileSummary* includes = nullptr;
  bool names_as_evidence = true, plain_names = true;
  std::optional<UnrealEra> era;
  std::vector<Variable> collected;  // the variables the declarations outside functions made
  std::vector<int> function_order;
  std::vector<std::string> function_names;  // in that order
  std::unordered_map<int, RunLog> runs;  // by function definition
};

ModelReuse::ModelReuse() = default;
ModelReuse::~ModelReuse() = default;

// The analysis itself; WorldModel keeps only its results.
class Analyzer {
 public:
  Analyzer(WorldModel& m, const ModelContext& context) : m_(m), t_(m.tree_), d_(m.data_), inc_(context.includes), context_(context) {}

  void run() {
    collect();
    prepare_reuse();
    for (int fn : function_order_) {
      if (replay(fn)) {
        ++m_.replayed_functions_;
        continue;
      }
      m_.analysed_functions_.push_back(fn);
      begin_run();
      analyze_function(fn, {});
      end_run(fn);
    }
    if (log_) context_.reuse->logs_[context_.variant] = std::move(log_);
    // A stage output named as world-space data holds what the file stores into it when every
    // store is classified and none is absolute (`cameraPosition = vec3(1.0)`): the name was wrong.
    for (const auto& [var, output] : named_outputs_) {
      if (!output.stored || output.unclassified || holds_absolute(output.stored_kind)) continue;
      Variable& v = m_.variables_[var];
      v.kind = output.stored_kind;
      std::erase_if(m_.holders_, [&](const AbsoluteHolder& h) { return h.site == v.decl; });
      reported_.erase(v.decl);
    }
    // A holder whose every use keeps only what float32 holds well is no hazard.
    std::erase_if(m_.holders_, [&](const AbsoluteHolder& h) {
      auto it = decl_var_.find(h.site);
      return it != decl_var_.end() && (m_.cleared_.count(it->second) || m_.only_harmless_uses(it->second));
    });
  }

 private:
  struct Frame {
    int function = -1;
    std::unordered_map<std::string, int> scope;  // name -> variable
    std::unordered_map<int, Kind> current;       // variable -> kind now
    Kind ret = Kind::unknown;
  };

  // ---- declarations -------------------------------------------------------------------------
  std::string_view type_of(int declaration) const {
    int type = t_.child_by_field(declaration, "type");
    return type >= 0 ? t_.text(type) : std::string_view();
  }

  int declarator_name(int d) const { return t_.declarator_name(d); }

  // A declaration whose HLSL semantic is SV_Position (masked out of the tree, read from the file):
  // the value is in clip space, whatever its name says.
  bool clip_semantic(int declaration) const {
    if (t_.lang != Lang::hlsl) return false;
    const std::string& src = t_.source->text();
    size_t end = t_.at(declaration).end;
    while (end < src.size() && src[end] != ';' && src[end] != ',' && src[end] != ')' && src[end] != '{') ++end;
    std::string text = src.substr(t_.at(declaration).begin, end - t_.at(declaration).begin);
    for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    size_t colon = text.rfind(':');
    return colon != std::string::npos && text.find("SV_POSITION", colon) != std::string::npos;
  }

  int new_variable(Variable v) {
    auto it = decl_var_.find(v.decl);
    if (it != decl_var_.end()) {
      touch_variable(it->second);
      return it->second;
    }
    int id = static_cast<int>(m_.variables_.size());
    decl_var_[v.decl] = id;
    if (run_) {
      run_->created.push_back(v);
      touched_variables_.emplace(id, std::nullopt);
    }
    m_.variables_.push_back(std::move(v));
    return id;
  }

  std::string function_name(int fn) const {
    int name = declarator_name(t_.child_by_field(fn, "declarator"));
    return name >= 0 ? std::string(t_.text(name)) : std::string();
  }

  void collect() {
    const auto& nodes = t_.nodes;
    for (int id = 0; id < static_cast<int>(nodes.size()); ++id) {
      std::string_view type = nodes[id].type;
      if (type == "function_definition") {
        int name = declarator_name(t_.child_by_field(id, "declarator"));
        if (name >= 0) functions_[std::string(t_.text(name))].push_back(id);
        function_order_.push_back(id);
      } else if (type == "struct_specifier") {
        collect_struct(id);
      } else if (type == "declaration" && t_.ancestor(id, "function_definition") < 0) {
        collect_global(id);
      }
    }
  }

  void collect_struct(int id) {
    int name = t_.child_by_field(id, "name");
    int body = t_.child_by_field(id, "body");
    if (name < 0 || body < 0) return;
    std::string owner(t_.text(name));
    for (int f : t_.named_children(body)) {
      if (!t_.is(f, "field_declaration")) continue;
      for (int c = t_.at(f).first_child; c >= 0; c = t_.at(c).next_sibling) {
        if (!t_.at(c).field || std::string_view(t_.at(c).field) != "declarator") continue;
        int n = declarator_name(c);
        if (n < 0) continue;
        Variable v = make_variable(std::string(t_.text(n)), std::string(type_of(f)), Variable::Role::field, n, f);
        v.owner = owner;
        v.clip = clip_semantic(f);
        int var = new_variable(std::move(v));
        fields_[owner + "." + std::string(t_.text(n))] = var;
        fields_by_name_[std::string(t_.text(n))].push_back(var);
      }
    }
  }

  void collect_global(int id) {
    auto words = leading_words(t_, id);
    int block = t_.ancestor(id, "linkage_specification");  // an HLSL cbuffer after masking
    bool uniform;
    if (t_.lang == Lang::hlsl) {
      uniform = block >= 0 || (!has_word(words, "static") && !has_word(words, "groupshared"));
    } else {
      uniform = has_word(words, "uniform");
    }
    // A GLSL interface block: its members are globals, reached directly or through its instance.
    for (int c : t_.named_children(id)) {
      if (!t_.is(c, "field_declaration_list")) continue;
      for (int f : t_.named_children(c)) {
        if (!t_.is(f, "field_declaration")) continue;
        int n = declarator_name(t_.child_by_field(f, "declarator"));
        if (n < 0) continue;
        add_global(f, n, std::string(type_of(f)), id, uniform, has_word(leading_words(t_, f), "precise"));
      }
      int after = t_.at(c).next_sibling;
      while (after >= 0 && !t_.at(after).named) after = t_.at(after).next_sibling;
      if (after >= 0 && t_.is(after, "identifier")) block_instances_.insert(std::string(t_.text(after)));
      return;
    }
    std::string type(type_of(id));
    for (int c = t_.at(id).first_child; c >= 0; c = t_.at(c).next_sibling) {
      if (!t_.at(c).field || std::string_view(t_.at(c).field) != "declarator") continue;
      int n = declarator_name(c);
      if (n < 0 || t_.is(c, "function_declarator")) continue;
      // A GLSL stage output: what this shader stores into it can overrule its name.
      bool output = t_.lang == Lang::glsl && has_word(words, "out") && !has_word(words, "in");
      // A GLSL stage input that another shader of the program writes (a sibling literal of a
      // script): it holds what that stage's output holds, which overrules its name when classified
      // and not absolute.
      std::optional<Kind> written;
      if (inc_ && t_.lang == Lang::glsl && (has_word(words, "in") || has_word(words, "varying")) && !has_word(words, "out"))
        if (auto it = inc_->globals.find(std::string(t_.text(n))); it != inc_->globals.end()) written = it->second;
      bool name_counts = !written || *written == Kind::unknown || holds_absolute(*written);
      int var = add_global(id, n, type, block, uniform, has_word(words, "precise"), output, name_counts);
      if (t_.is(c, "init_declarator")) m_.variables_[var].init = t_.child_by_field(c, "value");
      m_.variables_[var].private_global = !uniform && block < 0 && private_storage(words);
      if (written) hold(var, *written, -1);
    }
  }

  bool private_storage(const std::vector<std::string_view>& words) const {
    if (t_.lang == Lang::hlsl) return has_word(words, "static") && !has_word(words, "groupshared");
    for (std::string_view w : {"in", "out", "inout", "attribute", "varying", "buffer", "shared"})
      if (has_word(words, w)) return false;
    return true;
  }

  // `name_counts`: a naming convention may say what it holds.
  int add_global(int declaration, int name, std::string type, int block, bool uniform, bool precise, bool output = false,
                 bool name_counts = true) {
    Variable v = make_variable(std::string(t_.text(name)), std::move(type), Variable::Role::global, name, declaration);
    v.block = block;
    v.uniform = uniform;
    v.precise = precise;
    if (name_counts) v.kind = source_kind(Path{{v.name, false}}, true).value_or(Kind::unknown);
    int var = new_variable(std::move(v));
    globals_[m_.variables_[var].name] = var;
    // A GLSL varying named as a world position (`in vec3 vWorldPosition`) holds one.
    if (!uniform) hold(var, m_.variables_[var].kind, -1);
    if (output && m_.variables_[var].kind != Kind::unknown) named_outputs_[var] = {};
    return var;
  }

  // ---- functions ----------------------------------------------------------------------------
  Summary analyze_function(int fn, const std::vector<Kind>& args) {
    auto key = std::make_pair(fn, args);
    if (run_) {
      run_->functions.push_back(fn);
      if (touched_memo_.insert(key).second) run_->memo_before.emplace_back(key, memo_entry(key));
    }
    if (auto it = memo_.find(key); it != memo_.end()) return it->second;
    if (active_.count(fn)) return {};
    active_.insert(fn);
    Frame frame;
    frame.function = fn;
    Frame* outer = frame_;
    frame_ = &frame;

    std::vector<int> params;
    int declarator = t_.child_by_field(fn, "declarator");
    while (declarator >= 0 && !t_.is(declarator, "function_declarator"))
      declarator = t_.child_by_field(declarator, "declarator");
    int list = declarator >= 0 ? t_.child_by_field(declarator, "parameters") : -1;
    if (list >= 0) {
      for (int p : t_.named_children(list)) {
        if (!t_.is(p, "parameter_declaration")) continue;
        int n = declarator_name(t_.child_by_field(p, "declarator"));
        if (n < 0) continue;
        auto words = leading_words(t_, p);
        Variable v = make_variable(std::string(t_.text(n)), std::string(type_of(p)), Variable::Role::parameter, n, p, fn);
        v.output = has_word(words, "out") || has_word(words, "inout");
        v.precise = has_word(words, "precise");
        v.clip = clip_semantic(p);
        int var = new_variable(std::move(v));
        Kind k = params.size() < args.size() ? args[params.size()] : Kind::unknown;
        frame.scope[m_.variables_[var].name] = var;
        params.push_back(var);
        hold(var, k, -1);
      }
    }
    int body = t_.child_by_field(fn, "body");
    if (body >= 0) walk(body);

    Summary s;
    s.ret = frame.ret;
    for (int var : params) s.outs.push_back(m_.variables_[var].output ? current(var) : Kind::unknown);
    if (args.empty()) {
      int name = declarator_name(t_.child_by_field(fn, "declarator"));
      if (name >= 0) {
        std::string n(t_.text(name));
        m_.returns_[n] = join(m_.returns_[n], s.ret);
        m_.return_types_[n] = std::string(type_of(fn));
        if (run_) {
          run_->returns.emplace_back(n, s.ret);
          run_->return_types.emplace_back(n, m_.return_types_[n]);
        }
      }
    }
    frame_ = outer;
    active_.erase(fn);
    memo_[key] = s;
    return s;
  }

  // Statements in order, without recursion: nesting depth is the file's, not the stack's.
  void walk(int body) {
    std::vector<int> stack{body};
    while (!stack.empty()) {
      int id = stack.back();
      stack.pop_back();
      std::string_view type = t_.at(id).type;
      if (type == "declaration") {
        declare_locals(id);
      } else if (type == "return_statement") {
        int value = t_.named_child(id);
        if (value >= 0) {
          Kind k = eval(value, 0);
          frame_->ret = join(frame_->ret, k);
          note_return(k);
        }
      } else if (is_expression(id)) {
        eval(id, 0);
      } else {
        std::vector<int> children = t_.named_children(id);
        for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
      }
    }
  }

  bool is_expression(int id) const {
    std::string_view type = t_.at(id).type;
    return ends_with(type, "_expression") || type == "identifier" || type == "initializer_list";
  }

  void declare_locals(int id) {
    std::string type(type_of(id));
    bool precise = has_word(leading_words(t_, id), "precise");
    for (int c = t_.at(id).first_child; c >= 0; c = t_.at(c).next_sibling) {
      if (!t_.at(c).field || std::string_view(t_.at(c).field) != "declarator") continue;
      int n = declarator_name(c);
      if (n < 0) continue;
      Variable v = make_variable(std::string(t_.text(n)), type, Variable::Role::local, n, id, frame_->function);
      v.precise = precise;
      int value = t_.is(c, "init_declarator") ? t_.child_by_field(c, "value") : -1;
      v.init = value;
      int var = new_variable(std::move(v));
      frame_->scope[m_.variables_[var].name] = var;
      Kind k = value >= 0 ? eval(value, 0) : Kind::unknown;
      if (is_3x3_type(type) && is_matrix(k)) k = Kind::rotation_matrix;
      hold(var, k, -1);
    }
  }

  void note_return(Kind k) {
    int fn = frame_->function;
    std::string_view type = type_of(fn);
    if (!holds_absolute(k) || !d_.is_float_type(type)) return;
    int name = declarator_name(t_.child_by_field(fn, "declarator"));
    if (name >= 0) report({AbsoluteHolder::What::return_value, name, std::string(t_.text(name)), std::string(type), k});
  }

  Kind current(int var) const {
    if (frame_) {
      auto it = frame_->current.find(var);
      if (it != frame_->current.end()) return it->second;
    }
    touch_variable(var);
    return m_.variables_[var].kind;
  }

  // `var` now holds `k`: remember it, and report a float-typed holder of absolute data.
  void hold(int var, Kind k, int site) {
    touch_variable(var);
    if (auto it = named_outputs_.find(var); it != named_outputs_.end()) {
      it->second.stored = true;
      it->second.unclassified |= k == Kind::unknown;
      it->second.stored_kind = join(it->second.stored_kind, k);
    }
    Variable& v = m_.variables_[var];
    k = v.clip ? Kind::local : d_.named_kind(v.name, k);
    if (frame_ && v.role != Variable::Role::global && v.role != Variable::Role::field) frame_->current[var] = k;
    v.kind = join(v.kind, k);
    if (!holds_absolute(k) || v.uniform || !d_.is_float_type(v.type)) return;
    AbsoluteHolder::What what = v.role == Variable::Role::parameter ? AbsoluteHolder::What::parameter
                                : v.role == Variable::Role::field  ? AbsoluteHolder::What::field
                                                                   : AbsoluteHolder::What::variable;
    std::string name = v.role == Variable::Role::field ? v.owner + "." + v.name : v.name;
    report({what, site >= 0 ? site : v.decl, name, v.type, k});
  }

  void report(AbsoluteHolder h) {
    if (run_) run_->reports.push_back(h);
    if (reported_.insert(h.site).second) m_.holders_.push_back(std::move(h));
  }

  // ---- expressions --------------------------------------------------------------------------
  // The kind a source pattern gives a path. Naming conventions ("by-name") count for a global
  // the file declares (a uniform is named for what the host puts in it), and elsewhere only where
  // names are evidence (plain and UE4-era code).
  std::optional<Kind> source_kind(const Path& path, bool declared_global = false) {
    bool names = declared_global || m_.names_as_evidence_;
    std::string key = std::string(names ? "n:" : "s:");
    for (const auto& s : path) key += s.name + (s.call ? "()." : ".");
    auto it = source_cache_.find(key);
    if (it != source_cache_.end()) return it->second;
    std::optional<Kind> found;
    for (const auto& s : d_.sources)
      if ((!s.by_name || (names && (!s.plain_only || m_.plain_names_))) && s.pattern.matches(path)) {
        found = s.kind;
        break;
      }
    source_cache_.emplace(key, found);
    return found;
  }

  std::optional<FunctionRole> role_of(std::string_view name) const {
    Path p{{std::string(name), false}};
    for (const auto& f : d_.functions)
      if (f.pattern.matches(p)) return f.role;
    return std::nullopt;
  }

  int lookup(std::string_view name) const {
    if (frame_) {
      auto it = frame_->scope.find(std::string(name));
      if (it != frame_->scope.end()) return it->second;
    }
    auto g = globals_.find(std::string(name));
    return g != globals_.end() ? g->second : -1;
  }

  static void join_at(std::unordered_map<int, Kind>& kinds, int id, Kind k) {
    auto [it, inserted] = kinds.emplace(id, k);
    if (!inserted) it->second = join(it->second, k);
  }
  // The same on the model's kinds by node, where nothing recorded is Kind::unknown (its join with
  // any kind is that kind).
  void join_at_node(int id, Kind k) {
    Kind& at = m_.kinds_[static_cast<size_t>(id)];
    at = join(at, k);
  }

  Kind record(int id, Kind k) {
    join_at_node(id, k);
    if (run_) join_at(run_kinds_, id, k);
    return k;
  }

  void refer(int identifier, int var) {
    m_.refs_[identifier] = var;
    if (run_) run_->refs.emplace_back(identifier, m_.variables_[var].decl);
  }

  Kind eval(int id, int depth) {
    if (depth > kMaxDepth) {
      m_.too_deep_.push_back(id);
      if (run_) run_->too_deep.push_back(id);
      return Kind::unknown;
    }
    return record(id, eval_node(id, depth + 1));
  }

  Kind eval_node(int id, int depth) {
    std::string_view type = t_.at(id).type;
    if (type == "parenthesized_expression") {
      int inner = t_.named_child(id);
      return inner >= 0 ? eval(inner, depth) : Kind::unknown;
    }
    if (type == "identifier") return eval_identifier(id);
    if (type == "number_literal" || type == "true" || type == "false") return Kind::local;
    if (type == "field_expression") return eval_field(id, depth);
    if (type == "subscript_expression") return eval_subscript(id, depth);
    if (type == "call_expression") return eval_call(id, depth);
    if (type == "binary_expression") return eval_binary(id, depth);
    if (type == "assignment_expression") return eval_assignment(id, depth);
    if (type == "cast_expression") {
      int value = t_.child_by_field(id, "value");
      Kind k = value >= 0 ? eval(value, depth) : Kind::unknown;
      int target = t_.child_by_field(id, "type");
      if (target >= 0 && is_3x3_type(t_.text(target)) && is_matrix(k)) return Kind::rotation_matrix;
      return k;
    }
    if (type == "unary_expression") {
      int arg = t_.child_by_field(id, "argument");
      Kind k = arg >= 0 ? eval(arg, depth) : Kind::unknown;
      int op = t_.child_by_field(id, "operator");
      return op >= 0 && t_.text(op) == "-" ? negate(k) : (op >= 0 && t_.text(op) == "!" ? Kind::local : k);
    }
    if (type == "conditional_expression") {
      int c = t_.child_by_field(id, "condition");
      if (c >= 0) eval(c, depth);
      int a = t_.child_by_field(id, "consequence"), b = t_.child_by_field(id, "alternative");
      return join(a >= 0 ? eval(a, depth) : Kind::unknown, b >= 0 ? eval(b, depth) : Kind::unknown);
    }
    Kind k = Kind::unknown;
    bool last_only = type == "comma_expression";
    for (int c : t_.named_children(id)) {
      Kind ck = eval(c, depth);
      k = last_only ? ck : join(k, ck);
    }
    return (type == "initializer_list" || last_only) ? k : Kind::unknown;
  }

  Kind eval_identifier(int id) {
    std::string_view name = t_.text(id);
    int var = lookup(name);
    if (var >= 0) {
      refer(id, var);
      return current(var);
    }
    if (auto k = source_kind(Path{{std::string(name), false}})) return *k;
    if (inc_) {
      auto it = inc_->globals.find(std::string(name));
      if (it != inc_->globals.end()) return it->second;
    }
    return Kind::unknown;
  }

  Kind eval_field(int id, int depth) {
    int base = t_.child_by_field(id, "argument");
    int field = t_.child_by_field(id, "field");
    Kind base_kind = base >= 0 ? eval(base, depth) : Kind::unknown;
    if (auto p = m_.path(id)) {
      if (auto k = source_kind(*p)) return *k;
    }
    if (field < 0) return Kind::unknown;
    std::string name(t_.text(field));
    if (base >= 0 && t_.is(base, "identifier") && block_instances_.count(std::string(t_.text(base)))) {
      int var = lookup(name);
      if (var >= 0) {
        refer(field, var);
        return current(var);
      }
    }
    if (era_column() >= 0) {
      if (const auto* e = d_.engine_member(owner_of(base), name)) return era_column() > 0 && e->ue5_kind ? *e->ue5_kind : e->kind;
    }
    if (is_swizzle(name)) {
      if (is_matrix(base_kind)) return Kind::unknown;
      // `.w` of a position is its homogeneous coordinate or a packed scalar, not a coordinate.
      if ((name == "w" || name == "a") && base_kind != Kind::unknown) return Kind::local;
      return base_kind;
    }
    std::string by_owner = owner_of(base) + "." + name;
    touch_field(by_owner);
    auto it = field_kinds_.find(by_owner);
    if (it == field_kinds_.end()) {
      touch_field("." + name);
      it = field_kinds_.find("." + name);
    }
    return it != field_kinds_.end() ? it->second : Kind::unknown;
  }

  // 0, 1, 2 for UE4, UE 5.0-5.3, UE 5.4+ (the engine tables' columns); -1 outside Unreal code.
  int era_column() const {
    if (!m_.era_) return -1;
    return *m_.era_ == UnrealEra::ue4 ? 0 : *m_.era_ == UnrealEra::ue5_0 ? 1 : 2;
  }

  // The struct type of a field access's base, when the base is a known variable.
  std::string owner_of(int base) const {
    while (base >= 0 && t_.is(base, "parenthesized_expression")) base = t_.named_child(base);
    if (base >= 0 && t_.is(base, "field_expression")) {  // a.b.c: the type of a.b
      int field = t_.child_by_field(base, "field");
      return field >= 0 ? field_type(owner_of(t_.child_by_field(base, "argument")), std::string(t_.text(field))) : std::string();
    }
    if (base < 0 || !t_.is(base, "identifier")) return {};
    int var = lookup(t_.text(base));
    return var >= 0 ? m_.variables_[var].type : std::string();
  }

  // A struct field's declared type: in this file, else in an include; "" when unknown (an
  // unknown owner matches a field name that only one struct declares).
  std::string field_type(const std::string& owner, const std::string& name) const {
    if (auto it = fields_.find(owner + "." + name); it != fields_.end()) return m_.variables_[it->second].type;
    if (owner.empty())
      if (auto f = fields_by_name_.find(name); f != fields_by_name_.end() && f->second.size() == 1) return m_.variables_[f->second[0]].type;
    if (inc_)
      if (auto it = inc_->field_types.find(owner + "." + name); it != inc_->field_types.end()) return it->second;
    if (era_column() >= 0)
      if (const auto* e = d_.engine_member(owner, name)) return e->types[era_column()];
    if (!inc_) return {};
    if (!owner.empty()) return {};
    // A field name only one type of field in the includes has: indexed on first use (a UE file's
    // includes declare thousands of fields, and this is asked for every unknown owner). Read in
    // key order, a type that differs from the one found so far makes the name ambiguous.
    if (!include_field_by_name_) {
      include_field_by_name_.emplace();
      std::set<std::string> ambiguous;
      for (const auto& [key, type] : inc_->field_types) {
        size_t dot = key.rfind('.');
        if (dot == std::string::npos) continue;
        std::string field = key.substr(dot + 1);
        if (ambiguous.count(field)) continue;
        auto [it, added] = include_field_by_name_->emplace(field, type);
        if (added) continue;
        if (!it->second.empty() && it->second != type) {
          ambiguous.insert(field);
          it->second.clear();
        } else {
          it->second = type;
        }
      }
    }
    auto it = include_field_by_name_->find(name);
    return it != include_field_by_name_->end() ? it->second : std::string();
  }

  Kind eval_subscript(int id, int depth) {
    int base = t_.child_by_field(id, "argument");
    int index = t_.subscript_index(id);
    Kind k = base >= 0 ? eval(base, depth) : Kind::unknown;
    if (index >= 0) eval(index, depth);
    if (!is_matrix(k)) return k;
    // A name the file does not declare (an engine's array of matrices, bgfx's u_model[0]) is
    // indexed by element: the element is the matrix.
    if (t_.is(base, "identifier") && lookup(t_.text(base)) < 0) return k;
    // Row (HLSL) or column (GLSL) 3 of a 4x4 transform is its translation.
    bool translation = index >= 0 && t_.text(index) == "3";
    if (!translation) return Kind::direction;
    if (k == Kind::world_matrix) return Kind::absolute;
    if (k == Kind::translated_world_matrix) return Kind::translated;
    return Kind::unknown;
  }

  // An operand whose type is a matrix (`float4x4`, `mat4`, a matrix-typed variable or field).
  bool matrix_typed(int n) const {
    while (n >= 0 && t_.is(n, "parenthesized_expression")) n = t_.named_child(n);
    if (n < 0) return false;
    std::string type;
    if (t_.is(n, "identifier")) {
      int var = lookup(t_.text(n));
      if (var >= 0) type = m_.variables_[var].type;
    } else if (t_.is(n, "field_expression")) {
      int field = t_.child_by_field(n, "field");
      if (field >= 0) {
        auto it = fields_.find(owner_of(t_.child_by_field(n, "argument")) + "." + std::string(t_.text(field)));
        if (it != fields_.end()) type = m_.variables_[it->second].type;
      }
    } else if (t_.is(n, "call_expression") || t_.is(n, "cast_expression")) {
      int f = t_.child_by_field(n, t_.is(n, "call_expression") ? "function" : "type");
      if (f >= 0) type = std::string(t_.text(f));
    }
    return type.find('x') != std::string::npos ? d_.is_float_type(type) && type.back() != 'x' : type.rfind("mat", 0) == 0;
  }

  // A vector that a matrix transforms as a point (w = 1) rather than a direction (w = 0 or no w).
  bool is_point(int v) const {
    while (v >= 0 && (t_.is(v, "parenthesized_expression") || t_.is(v, "cast_expression")))
      v = t_.is(v, "cast_expression") ? t_.child_by_field(v, "value") : t_.named_child(v);
    if (v < 0) return true;
    if (t_.is(v, "call_expression")) {
      int fn = t_.child_by_field(v, "function");
      int args = t_.child_by_field(v, "arguments");
      std::string_view name = fn >= 0 ? t_.text(fn) : std::string_view();
      bool ctor4 = ends_with(name, "4") && d_.is_float_type(name);
      if (ctor4 && args >= 0) {
        auto list = t_.named_children(args);
        if (list.size() >= 2 && t_.is(list.back(), "number_literal")) {
          std::string_view w = t_.text(list.back());
          return w.find_first_of("123456789") != std::string_view::npos;
        }
      }
      if (d_.is_float_type(name) && ends_with(name, "3")) return false;
    }
    if (t_.is(v, "field_expression")) {
      int field = t_.child_by_field(v, "field");
      if (field >= 0 && is_swizzle(t_.text(field)) && t_.text(field).size() == 3) return false;
    }
    if (t_.is(v, "identifier")) {
      int var = lookup(t_.text(v));
      if (var >= 0 && ends_with(m_.variables_[var].type, "3")) return false;
    }
    return true;
  }

  // `as_point`: the function treats a 3-vector as a point (DFMultiply(float3, FDFMatrix)).
  Kind transform(int vec, Kind vk, Kind mk, bool as_point = false) {
    if (mk == Kind::rotation_matrix) return Kind::direction;
    if (!is_matrix(mk)) return Kind::unknown;
    if (vk == Kind::direction || (!as_point && !is_point(vec))) return Kind::direction;
    switch (mk) {
      case Kind::world_matrix: return Kind::absolute;
      case Kind::translated_world_matrix: return Kind::translated;
      default: return Kind::local;
    }
  }

  Kind eval_call(int id, int depth) {
    int fn = t_.child_by_field(id, "function");
    int args_node = t_.child_by_field(id, "arguments");
    std::vector<int> args = args_node >= 0 ? t_.named_children(args_node) : std::vector<int>{};
    std::vector<Kind> kinds;
    for (int a : args) kinds.push_back(eval(a, depth));
    if (fn < 0) return Kind::unknown;
    if (!t_.is(fn, "identifier")) {
      if (t_.is(fn, "field_expression")) {  // a method call: texture.Sample(...)
        int base = t_.child_by_field(fn, "argument");
        if (base >= 0) eval(base, depth);
      }
      return Kind::unknown;
    }
    std::string name(t_.text(fn));
    // A function this file defines is what it computes, whatever an engine function of that name does.
    if (functions_.count(name) == 0) {
      if (auto p = m_.path(id)) {
        if (auto k = source_kind(*p)) return *k;
      }
    }
    if (d_.is_float_type(name)) {  // a constructor: float4(P, 1), vec3(...), float3x3(M)
      Kind k = Kind::unknown;
      for (Kind a : kinds) k = join(k, a);
      if (is_3x3_type(name) && is_matrix(k)) return Kind::rotation_matrix;
      return k;
    }
    if (auto it = functions_.find(name); it != functions_.end()) return call_user(it->second, args, kinds);
    if (era_column() >= 0)
      if (auto e = d_.engine_functions.find(name); e != d_.engine_functions.end()) return e->second[era_column()];
    if (auto role = role_of(name)) return apply_role(*role, args, kinds);
    if (inc_) {
      auto it = inc_->function_returns.find(name);
      if (it != inc_->function_returns.end()) return it->second;
    }
    return Kind::unknown;
  }

  Kind apply_role(FunctionRole role, const std::vector<int>& args, const std::vector<Kind>& k) {
    Kind a = k.size() > 0 ? k[0] : Kind::unknown, b = k.size() > 1 ? k[1] : Kind::unknown;
    switch (role) {
      case FunctionRole::transform_point:
      case FunctionRole::transform:
        if (k.size() < 2) return a;
        if (is_matrix(a) && is_matrix(b)) return compose(a, b);
        if (is_matrix(b)) return transform(args[0], a, b, role == FunctionRole::transform_point);
        if (is_matrix(a)) return transform(args[1], b, a, role == FunctionRole::transform_point);
        // A matrix lwcport does not know (or any operand that is not a constant) maps the value
        // to a space it does not know either.
        if ((holds_absolute(a) && !constant(args[1])) || (holds_absolute(b) && !constant(args[0]))) return Kind::unknown;
        if (role == FunctionRole::transform && (matrix_typed(args[0]) || matrix_typed(args[1]))) return Kind::unknown;
        return scale(a, b);
      case FunctionRole::direction: return Kind::direction;
      case FunctionRole::local: return Kind::local;
      case FunctionRole::join: {
        Kind j = Kind::unknown;
        for (size_t i = 0; i < k.size() && i < 2; ++i) j = join(j, k[i]);
        return j;
      }
      case FunctionRole::invert: return invert(a);
      case FunctionRole::same: return a;
      case FunctionRole::world_value: return a == Kind::unknown ? Kind::absolute : a;
      case FunctionRole::add: return add(a, b);
      case FunctionRole::subtract: return subtract(a, b);
      case FunctionRole::translated:
        if (a == Kind::absolute || a == Kind::world_matrix || b == Kind::world_matrix || b == Kind::camera_offset ||
            a == Kind::unknown || a == Kind::local)
          return is_matrix(a) ? Kind::translated_world_matrix : Kind::translated;
        return Kind::unknown;
    }
    return Kind::unknown;
  }

  Kind call_user(const std::vector<int>& overloads, const std::vector<int>& args, const std::vector<Kind>& kinds) {
    int fn = overloads.front();
    for (int candidate : overloads) {
      int d = t_.child_by_field(candidate, "declarator");
      while (d >= 0 && !t_.is(d, "function_declarator")) d = t_.child_by_field(d, "declarator");
      int list = d >= 0 ? t_.child_by_field(d, "parameters") : -1;
      if (list >= 0 && t_.named_children(list).size() == args.size()) fn = candidate;
      if (run_) run_->functions.push_back(candidate);
    }
    bool interesting = std::any_of(kinds.begin(), kinds.end(), [](Kind k) { return k != Kind::unknown && k != Kind::local; });
    Summary s = analyze_function(fn, interesting ? kinds : std::vector<Kind>{});
    for (size_t i = 0; i < s.outs.size() && i < args.size(); ++i)
      if (s.outs[i] != Kind::unknown) assign(args[i], s.outs[i]);
    return s.ret;
  }

  Kind eval_binary(int id, int depth) {
    int l = t_.child_by_field(id, "left"), r = t_.child_by_field(id, "right");
    int op_node = t_.child_by_field(id, "operator");
    Kind a = l >= 0 ? eval(l, depth) : Kind::unknown;
    Kind b = r >= 0 ? eval(r, depth) : Kind::unknown;
    std::string_view op = op_node >= 0 ? t_.text(op_node) : std::string_view();
    return binary(op, l, a, r, b);
  }

  Kind binary(std::string_view op, int l, Kind a, int r, Kind b) {
    // A position minus a value of unknown space that is named as a position is a difference of
    // two positions (a direction), not a position: unknown, as the space of that value is.
    if (op == "-" && ((holds_absolute(a) && b == Kind::unknown && named_position(r)) ||
                      (holds_absolute(b) && a == Kind::unknown && named_position(l))))
      return Kind::unknown;
    if (op == "+") return add(a, b);
    if (op == "-") return subtract(a, b);
    if (op == "*" && (is_matrix(a) || is_matrix(b) || matrix_typed(l) || matrix_typed(r))) {
      if (t_.lang == Lang::glsl) {
        if (is_matrix(a) && is_matrix(b)) return compose(b, a);  // column vectors: b applies first
        if (is_matrix(a)) return transform(r, b, a);
        if (is_matrix(b)) return transform(l, a, b);
      }
      return Kind::unknown;  // a product with a matrix lwcport does not know (or HLSL's component-wise one)
    }
    if (op == "*" || op == "/") {
      // Scaled by a variable, a position moves to another space (grid cells, a unit volume):
      // only a constant (a literal, an ALL_CAPS macro such as CENTIMETER_TO_KILOMETER) or the
      // homogeneous divide keeps it.
      if ((holds_absolute(a) && !constant(r)) || (holds_absolute(b) && !constant(l))) return Kind::unknown;
      return scale(a, b);
    }
    return Kind::local;  // comparisons, logic, bit operations
  }

  bool constant(int n) const {
    while (n >= 0 && t_.is(n, "parenthesized_expression")) n = t_.named_child(n);
    if (n < 0) return false;
    if (t_.is(n, "number_literal")) return true;
    if (t_.is(n, "unary_expression")) return constant(t_.child_by_field(n, "argument"));
    // The homogeneous divide (P.xyz / P.w) keeps the position where it is.
    if (t_.is(n, "field_expression") && t_.text(t_.child_by_field(n, "field")) == "w") return true;
    if (!t_.is(n, "identifier")) return false;
    std::string_view w = t_.text(n);
    return w.size() > 1 && std::all_of(w.begin(), w.end(), [](char c) { return std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'; });
  }

  // An expression whose name (its variable, or its last field) says it is a position.
  bool named_position(int n) const {
    while (n >= 0 && (t_.is(n, "parenthesized_expression") ||
                      (t_.is(n, "field_expression") && is_swizzle(t_.text(t_.child_by_field(n, "field"))))))
      n = t_.is(n, "parenthesized_expression") ? t_.named_child(n) : t_.child_by_field(n, "argument");
    if (n < 0) return false;
    std::string_view name;
    if (t_.is(n, "identifier")) name = t_.text(n);
    else if (t_.is(n, "field_expression") && t_.child_by_field(n, "field") >= 0) name = t_.text(t_.child_by_field(n, "field"));
    for (std::string_view w : {"Pos", "pos", "Origin", "origin", "Center", "center"})
      if (name.find(w) != std::string_view::npos) return true;
    return false;
  }

  Kind eval_assignment(int id, int depth) {
    int l = t_.child_by_field(id, "left"), r = t_.child_by_field(id, "right");
    int op_node = t_.child_by_field(id, "operator");
    std::string_view op = op_node >= 0 ? t_.text(op_node) : "=";
    Kind k = r >= 0 ? eval(r, depth) : Kind::unknown;
    if (op != "=" && l >= 0) k = binary(op.substr(0, op.size() - 1), l, eval(l, depth), r, k);
    else if (l >= 0 && !t_.is(l, "identifier")) eval(l, depth);  // field bases and indices are uses too
    if (l >= 0) assign(l, k);
    return k;
  }

  void assign(int lhs, Kind k) {
    while (lhs >= 0 && t_.is(lhs, "parenthesized_expression")) lhs = t_.named_child(lhs);
    if (lhs < 0) return;
    if (t_.is(lhs, "identifier")) {
      int var = lookup(t_.text(lhs));
      if (var >= 0) {
        refer(lhs, var);
        hold(var, k, -1);
      }
      return;
    }
    if (t_.is(lhs, "subscript_expression") || (t_.is(lhs, "field_expression") && is_swizzle(t_.text(t_.child_by_field(lhs, "field"))) &&
                                                t_.is(t_.child_by_field(lhs, "argument"), "subscript_expression"))) {
      int sub = t_.is(lhs, "subscript_expression") ? lhs : t_.child_by_field(lhs, "argument");
      int base = t_.child_by_field(sub, "argument");
      int index = t_.subscript_index(sub);
      int var = base >= 0 && t_.is(base, "identifier") ? lookup(t_.text(base)) : -1;
      // M[3] = vec4(0, 0, 0, 1): the translation of a matrix is cleared, and it only rotates now
      // (the relative-to-eye pattern of globe engines).
      if (var >= 0 && is_matrix(current(var)) && index >= 0 && t_.text(index) == "3" && !holds_absolute(k)) {
        refer(base, var);
        m_.cleared_.insert(var);
        if (run_) run_->cleared.push_back(m_.variables_[var].decl);
        if (frame_) frame_->current[var] = Kind::rotation_matrix;
        return;
      }
      if (holds_absolute(k)) assign(base, k);
      return;
    }
    if (!t_.is(lhs, "field_expression")) return;
    int base = t_.child_by_field(lhs, "argument");
    int field = t_.child_by_field(lhs, "field");
    if (field < 0) return;
    std::string name(t_.text(field));
    if (is_swizzle(name)) {
      if (holds_absolute(k)) assign(base, k);
      return;
    }
    std::string owner = owner_of(base);
    touch_field(owner + "." + name);
    touch_field("." + name);
    Kind& by_owner = field_kinds_[owner + "." + name];
    by_owner = join(by_owner, k);
    Kind& by_name = field_kinds_["." + name];
    by_name = join(by_name, k);
    // Report at the struct's field declaration when it is in this file, else at the assignment.
    int var = -1;
    if (auto it = fields_.find(owner + "." + name); it != fields_.end()) var = it->second;
    else if (auto f = fields_by_name_.find(name); f != fields_by_name_.end() && f->second.size() == 1) var = f->second[0];
    if (var >= 0) {
      hold(var, k, -1);
      return;
    }
    // A field declared elsewhere: reported at the assignment, only when its declared type is
    // known to be a float (a header's struct the summaries read); an unknown type is not guessed.
    k = d_.named_kind(name, k);
    std::string type = field_type(owner, name);
    if (holds_absolute(k) && lookup(name) < 0 && !type.empty() && d_.is_float_type(type))
      report({AbsoluteHolder::What::field, lhs, std::string(t_.text(lhs)), type, k});
  }

  // ---- replaying the document's last model (ModelReuse) ------------------------------------
  // This model's log, when the document keeps one; the last model's, when it ran on the tree this
  // tree's parse edited, with the same data and context, and the declarations outside functions
  // made the same variables.
  void prepare_reuse() {
    if (!context_.reuse) return;
    if (t_.number == 0) {  // a tree the next parse will not edit (lang/syntax.h): nothing to keep
      context_.reuse->logs_.erase(context_.variant);
      return;
    }
    log_ = std::make_unique<ModelReuse::Log>();
    log_->tree = t_.number;
    log_->data = &d_;
    log_->includes = inc_;
    log_->names_as_evidence = m_.names_as_evidence_;
    log_->plain_names = m_.plain_names_;
    log_->era = m_.era_;
    log_->collected = m_.variables_;
    log_->function_order = function_order_;
    for (int fn : function_order_) log_->function_names.push_back(function_name(fn));
    auto it = context_.reuse->logs_.find(context_.variant);
    if (it == context_.reuse->logs_.end() || t_.reused_from == 0) return;
    ModelReuse::Log& old = *it->second;
    if (old.tree != t_.reused_from || old.data != &d_ || old.includes != inc_ || old.names_as_evidence != m_.names_as_evidence_ ||
        old.plain_names != m_.plain_names_ || old.era != m_.era_)
      return;
    to_old_.assign(t_.nodes.size(), kGone);
    for (const SyntaxTree::Reused& r : t_.reused) {
      if (to_new_.size() < static_cast<size_t>(r.there + r.count)) to_new_.resize(r.there + r.count, kGone);
      for (int32_t k = 0; k < r.count; ++k) {
        to_old_[r.here + k] = r.there + k;
        to_new_[r.there + k] = r.here + k;
      }
    }
    if (old.collected.size() != m_.variables_.size()) return;
    for (size_t i = 0; i < old.collected.size(); ++i)
      if (!(moved(old.collected[i]) == m_.variables_[i])) return;
    // The same functions by name in the same order (an edited one has no old node).
    if (old.function_names != log_->function_names) return;
    for (size_t i = 0; i < function_order_.size(); ++i)
      if (new_id(old.function_order[i]) != function_order_[i] && (new_id(old.function_order[i]) >= 0 || to_old_[function_order_[i]] >= 0))
        return;
    old_ = &old;
  }

  static constexpr int kGone = -2;  // a node of the last tree this tree does not have
  int new_id(int old) const { return old < 0 ? old : static_cast<size_t>(old) < to_new_.size() ? to_new_[old] : kGone; }

  // A variable of the last model as this tree has it (node ids moved).
  Variable moved(Variable v) const {
    for (int* n : {&v.decl, &v.declaration, &v.function, &v.init, &v.block}) *n = new_id(*n);
    return v;
  }

  VariableState variable_state(int var) const {
    auto it = named_outputs_.find(var);
    return {m_.variables_[var].kind, it != named_outputs_.end() ? std::optional<NamedOutput>(it->second) : std::nullopt};
  }

  std::optional<Summary> memo_entry(const MemoKey& key) const {
    auto it = memo_.find(key);
    return it != memo_.end() ? std::optional<Summary>(it->second) : std::nullopt;
  }

  std::optional<Kind> field_kind(const std::string& key) const {
    auto it = field_kinds_.find(key);
    return it != field_kinds_.end() ? std::optional<Kind>(it->second) : std::nullopt;
  }

  // The first time the analysis being recorded reads or changes a part of the state: as it was.
  void touch_variable(int var) const {
    if (run_ && !touched_variables_.count(var)) touched_variables_.emplace(var, variable_state(var));
  }
  void touch_field(const std::string& key) {
    if (run_ && touched_fields_.insert(key).second) run_->fields_before.emplace_back(key, field_kind(key));
  }

  void begin_run() {
    if (!log_) return;
    current_run_ = {};
    run_ = &current_run_;
  }

  void end_run(int fn) {
    if (!run_) return;
    for (const auto& [var, before] : touched_variables_) {
      run_->variables_before.emplace_back(m_.variables_[var].decl, before);
      run_->variables_after.emplace_back(m_.variables_[var].decl, variable_state(var));
    }
    for (const MemoKey& key : touched_memo_)
      if (auto s = memo_entry(key)) run_->memo_after.emplace_back(key, *s);
    for (const std::string& key : touched_fields_)
      if (auto k = field_kind(key)) run_->fields_after.emplace_back(key, *k);
    run_->kinds.assign(run_kinds_.begin(), run_kinds_.end());
    touched_variables_.clear();
    touched_memo_.clear();
    touched_fields_.clear();
    run_kinds_.clear();
    log_->runs[fn] = std::move(current_run_);
    run_ = nullptr;
  }

  // The last model's analysis of this function, applied to this one, when everything it read is
  // as it was: the functions it read are unchanged (copied from the last tree) and the state it
  // touched holds what it held then.
  bool replay(int fn) {
    if (!old_ || to_old_[fn] < 0) return false;
    auto found = old_->runs.find(to_old_[fn]);
    if (found == old_->runs.end()) return false;
    const RunLog& r = found->second;
    auto memo_key = [&](const MemoKey& key) { return MemoKey{new_id(key.first), key.second}; };
    auto variable = [&](int decl) {
      auto it = decl_var_.find(new_id(decl));
      return it != decl_var_.end() ? it->second : -1;
    };
    for (int f : r.functions)
      if (new_id(f) < 0) return false;
    for (const auto& [decl, before] : r.variables_before) {
      if (new_id(decl) < 0) return false;
      int var = variable(decl);
      if (before ? var < 0 || !(variable_state(var) == *before) : var >= 0) return false;
    }
    for (const auto& [key, before] : r.memo_before)
      if (memo_entry(memo_key(key)) != before) return false;
    for (const auto& [key, before] : r.fields_before)
      if (field_kind(key) != before) return false;

    // Valid: the log moves to this model, its nodes renumbered for this tree, and is applied.
    RunLog now = std::move(found->second);
    for (std::vector<int>* nodes : {&now.functions, &now.too_deep, &now.cleared})
      for (int& n : *nodes) n = new_id(n);
    for (Variable& v : now.created) v = moved(std::move(v));
    for (auto& [decl, state] : now.variables_before) decl = new_id(decl);
    for (auto& [decl, state] : now.variables_after) decl = new_id(decl);
    for (auto& [key, summary] : now.memo_before) key.first = new_id(key.first);
    for (auto& [key, summary] : now.memo_after) key.first = new_id(key.first);
    for (auto& [node, k] : now.kinds) node = new_id(node);
    for (auto& [identifier, decl] : now.refs) identifier = new_id(identifier), decl = new_id(decl);
    for (AbsoluteHolder& h : now.reports) h.site = new_id(h.site);

    auto here = [&](int decl) { return decl_var_.at(decl); };
    for (const Variable& v : now.created) new_variable(v);
    for (const auto& [decl, after] : now.variables_after) {
      int var = here(decl);
      m_.variables_[var].kind = after.kind;
      if (after.output) named_outputs_[var] = *after.output;
    }
    for (const auto& [key, after] : now.memo_after) memo_[key] = after;
    for (const auto& [key, after] : now.fields_after) field_kinds_[key] = after;
    for (const auto& [node, k] : now.kinds) join_at_node(node, k);
    for (const auto& [identifier, decl] : now.refs) m_.refs_[identifier] = here(decl);
    for (const AbsoluteHolder& h : now.reports) report(h);
    m_.too_deep_.insert(m_.too_deep_.end(), now.too_deep.begin(), now.too_deep.end());
    for (int decl : now.cleared) m_.cleared_.insert(here(decl));
    for (const auto& [name, k] : now.returns) m_.returns_[name] = join(m_.returns_[name], k);
    for (const auto& [name, type] : now.return_types) m_.return_types_[name] = type;
    log_->runs[fn] = std::move(now);  // old_ is set only beside a log_
    return true;
  }

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
};

WorldModel::WorldModel(const SyntaxTree& tree, const WorldData& data, const ModelContext& context)
    : tree_(tree), data_(data), names_as_evidence_(context.names_as_evidence), plain_names_(context.plain_names), era_(context.era), includes_(context.includes) {
  kinds_.assign(tree.nodes.size(), Kind::unknown);
  refs_.assign(tree.nodes.size(), -1);
  declared_at_.assign(tree.nodes.size(), -1);
  Analyzer(*this, context).run();
  for (size_t i = 0; i < variables_.size(); ++i) {
    const Variable& v = variables_[i];
    if (v.decl >= 0 && declared_at_[v.decl] < 0) declared_at_[v.decl] = static_cast<int>(i);
    if (v.role == Variable::Role::global) globals_by_name_[v.name].push_back(static_cast<int>(i));
  }
}

WorldModel::~WorldModel() = default;

}  // namespace lwc
