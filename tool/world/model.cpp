#include "world/model.h"
#include "world/analyzer.h"

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

}  // namespace

namespace analysis {

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

bool has_word(const std::vector<std::string_view>& words, std::string_view w) {
  return std::find(words.begin(), words.end(), w) != words.end();
}

Variable make_variable(std::string name, std::string type, Variable::Role role, int decl, int declaration,
                              int function) {
  Variable v;
  v.name = std::move(name);
  v.type = std::move(type);
  v.role = role;
  v.decl = decl;
  v.declaration = declaration;
  v.function = function;
  return v;
}

}  // namespace analysis

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

bool named_as_point(std::string_view name) {
  for (std::string_view w : {"Pos", "Center", "Centre", "Origin", "Location", "Point"})
    if (name.find(w) != std::string_view::npos) return true;
  return false;
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

WorldData WorldData::load(const nlohmann::json& ws, const nlohmann::json& extra_sources, Lang lang, bool host_rebases) {
  WorldData d;
  // Relative to the host's render origin: absolute world data becomes translated (origin-relative).
  auto rebased = [&](Kind k) {
    if (!host_rebases) return k;
    return k == Kind::absolute ? Kind::translated : k == Kind::world_matrix ? Kind::translated_world_matrix
                                                  : k == Kind::from_world_matrix ? Kind::from_translated_matrix : k;
  };
  for (const auto& t : ws.at("float-types")) d.float_types.push_back(t.get<std::string>());
  auto add_sources = [&](const nlohmann::json& list, std::string_view where, bool builtin) {
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
      if (applies_to(s, lang)) d.sources.push_back({pattern, builtin ? rebased(*kind) : *kind, plain_only || by_name == true, plain_only});
    }
  };
  // The project's sources come first so they can override the built-in ones.
  if (extra_sources.is_array()) add_sources(extra_sources, "world-sources", false);
  add_sources(ws.at("sources"), "rules/world-space.json", true);
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
  d.twins.engine_members = twins.at("engine-members").get<std::map<std::string, std::map<std::string, std::string>>>();
  d.twins.struct_members = twins.at("struct-members").get<std::map<std::string, std::map<std::string, std::string>>>();
  d.twins.engine_globals = twins.at("engine-globals").get<std::map<std::string, std::string>>();
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
  for (const auto& [name, e] : ws.at("engine").at("function-types").items())
    d.engine_function_types[name] = {e.at(0).get<std::string>(), e.at(1).get<std::string>(), e.at(2).get<std::string>()};
  for (const auto& [name, e] : ws.at("engine").at("translated-parameters").items()) {
    std::optional<UnrealEra> from = parse_unreal_era(e.at(1).get<std::string>());
    if (!from) throw std::runtime_error("world-space.json: translated-parameters: bad era for " + name);
    // One parameter's index, or a list of them.
    std::vector<size_t> indices = e.at(0).is_array() ? e.at(0).get<std::vector<size_t>>() : std::vector<size_t>{e.at(0).get<size_t>()};
    d.engine_translated_parameters[name] = {std::move(indices), *from};
  }
  for (const auto& [name, e] : ws.at("engine").at("view-members-translated-in-place").items()) {
    std::optional<UnrealEra> from = parse_unreal_era(e.at(1).get<std::string>());
    if (!from) throw std::runtime_error("world-space.json: view-members-translated-in-place: bad era for " + name);
    d.view_translated_in_place[name] = {e.at(0).get<std::string>() == "plane", *from};
  }
  d.engine_objects = ws.at("engine").at("objects").get<std::map<std::string, std::string>>();
  d.uniform_buffer = ws.at("engine").at("uniform-buffer").get<std::array<std::string, 2>>();
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

bool WorldData::is_matrix_type(std::string_view type) const {
  return type.find('x') != std::string_view::npos ? is_float_type(type) && type.back() != 'x' : type.rfind("mat", 0) == 0;
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

ModelReuse::ModelReuse() = default;
ModelReuse::~ModelReuse() = default;

namespace analysis {

void Analyzer::run() {
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
  if (m_.era_ == UnrealEra::ue4) engine_contract_parameters();
  absolute_by_translation();
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

std::string_view Analyzer::type_of(int declaration) const {
  int type = t_.child_by_field(declaration, "type");
  return type >= 0 ? t_.text(type) : std::string_view();
}

bool Analyzer::clip_semantic(int declaration) const {
  if (t_.lang != Lang::hlsl) return false;
  const std::string& src = t_.source->text();
  size_t end = t_.at(declaration).end;
  while (end < src.size() && src[end] != ';' && src[end] != ',' && src[end] != ')' && src[end] != '{') ++end;
  std::string text = src.substr(t_.at(declaration).begin, end - t_.at(declaration).begin);
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  size_t colon = text.rfind(':');
  return colon != std::string::npos && text.find("SV_POSITION", colon) != std::string::npos;
}

int Analyzer::new_variable(Variable v) {
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

std::string Analyzer::function_name(int fn) const {
  int name = declarator_name(t_.child_by_field(fn, "declarator"));
  return name >= 0 ? std::string(t_.text(name)) : std::string();
}

void Analyzer::collect() {
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

void Analyzer::collect_struct(int id) {
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

bool Analyzer::custom_node_body() const {
  if (!custom_node_body_) {
    custom_node_body_ = false;
    for (int r : t_.of_type("return_statement"))
      if (t_.ancestor(r, "function_definition") < 0) custom_node_body_ = true;
  }
  return *custom_node_body_;
}

void Analyzer::collect_global(int id) {
  auto words = leading_words(t_, id);
  int block = t_.ancestor(id, "linkage_specification");  // an HLSL cbuffer after masking
  bool uniform;
  if (t_.lang == Lang::hlsl) {
    uniform = block >= 0 || (!has_word(words, "static") && !has_word(words, "groupshared") && !custom_node_body());
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

bool Analyzer::private_storage(const std::vector<std::string_view>& words) const {
  if (t_.lang == Lang::hlsl) return has_word(words, "static") && !has_word(words, "groupshared");
  for (std::string_view w : {"in", "out", "inout", "attribute", "varying", "buffer", "shared"})
    if (has_word(words, w)) return false;
  return true;
}

Summary Analyzer::analyze_function(int fn, const std::vector<Kind>& args) {
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

void Analyzer::walk(int body) {
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

bool Analyzer::is_expression(int id) const {
  std::string_view type = t_.at(id).type;
  return ends_with(type, "_expression") || type == "identifier" || type == "initializer_list";
}

void Analyzer::declare_locals(int id) {
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

void Analyzer::note_return(Kind k) {
  int fn = frame_->function;
  std::string_view type = type_of(fn);
  if (!holds_absolute(k) || !d_.is_float_type(type)) return;
  int name = declarator_name(t_.child_by_field(fn, "declarator"));
  if (name >= 0) report({AbsoluteHolder::What::return_value, name, std::string(t_.text(name)), std::string(type), k});
}

Kind Analyzer::current(int var) const {
  if (frame_) {
    auto it = frame_->current.find(var);
    if (it != frame_->current.end()) return it->second;
  }
  touch_variable(var);
  return m_.variables_[var].kind;
}

void Analyzer::hold(int var, Kind k, int site) {
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

void Analyzer::report(AbsoluteHolder h) {
  if (run_) run_->reports.push_back(h);
  if (reported_.insert(h.site).second) m_.holders_.push_back(std::move(h));
}

int Analyzer::add_global(int declaration, int name, std::string type, int block, bool uniform, bool precise, bool output,
                 bool name_counts) {
  Variable v = make_variable(std::string(t_.text(name)), std::move(type), Variable::Role::global, name, declaration);
  v.block = block;
  v.uniform = uniform;
  v.precise = precise;
  if (name_counts) v.kind = source_kind(Path{{v.name, false}}, true).value_or(Kind::unknown);
  // A 3x3 matrix holds no translation, whatever its name says (`TangentToWorld`).
  if (is_3x3_type(v.type) && is_matrix(v.kind)) v.kind = Kind::rotation_matrix;
  int var = new_variable(std::move(v));
  globals_[m_.variables_[var].name] = var;
  // A GLSL varying named as a world position (`in vec3 vWorldPosition`) holds one.
  if (!uniform) hold(var, m_.variables_[var].kind, -1);
  if (output && m_.variables_[var].kind != Kind::unknown) named_outputs_[var] = {};
  return var;
}

}  // namespace analysis

WorldModel::WorldModel(const SyntaxTree& tree, const WorldData& data, const ModelContext& context)
    : tree_(tree), data_(data), names_as_evidence_(context.names_as_evidence), plain_names_(context.plain_names), era_(context.era), includes_(context.includes) {
  kinds_.assign(tree.nodes.size(), Kind::unknown);
  refs_.assign(tree.nodes.size(), -1);
  declared_at_.assign(tree.nodes.size(), -1);
  analysis::Analyzer(*this, context).run();
  for (size_t i = 0; i < variables_.size(); ++i) {
    const Variable& v = variables_[i];
    if (v.decl >= 0 && declared_at_[v.decl] < 0) declared_at_[v.decl] = static_cast<int>(i);
    if (v.role == Variable::Role::global) globals_by_name_[v.name].push_back(static_cast<int>(i));
  }
}

WorldModel::~WorldModel() = default;

}  // namespace lwc
