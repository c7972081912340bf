#include "world/provenance.h"

#include <fmt/format.h>

#include <set>

#include "core/source.h"

namespace lwc {

std::string kind_words(Kind kind) {
  switch (kind) {
    case Kind::unknown: return "of unknown space";
    case Kind::local: return "small (local, clip or a scalar)";
    case Kind::direction: return "a direction (no position)";
    case Kind::translated: return "a translated-world (camera-relative) position";
    case Kind::absolute: return "an absolute world position";
    case Kind::camera_offset: return "the pre-view translation (minus the camera's absolute position)";
    case Kind::world_matrix: return "a matrix to absolute world (its translation is an absolute position)";
    case Kind::translated_world_matrix: return "a matrix to translated world";
    case Kind::from_world_matrix: return "a matrix from absolute world (its translation is absolute)";
    case Kind::from_translated_matrix: return "a matrix from translated world";
    case Kind::rotation_matrix: return "a rotation (a 3x3 matrix: directions only)";
    case Kind::local_matrix: return "a matrix between small spaces";
  }
  return "of unknown space";
}

namespace {

bool worth_tracing(Kind k) { return k != Kind::unknown && k != Kind::local && k != Kind::direction; }

// The kinds' order of concern: what makes a value most absolute is what explains it.
int concern(Kind k) { return holds_absolute(k) ? 3 : worth_tracing(k) ? 2 : k == Kind::unknown ? 0 : 1; }

bool ends_a_value(const SyntaxTree& t, int node) {
  for (const char* type : {"expression_statement", "compound_statement", "function_definition", "declaration", "translation_unit",
                           "field_declaration", "parameter_declaration", "return_statement", "struct_specifier"})
    if (t.is(node, type)) return true;
  return false;
}

// The function definition whose name `node` is, or -1.
int function_named_by(const SyntaxTree& t, int node) {
  if (node < 0 || !t.is(node, "identifier")) return -1;
  int function = t.ancestor(node, "function_definition");
  return function >= 0 && t.declarator_name(t.child_by_field(function, "declarator")) == node ? function : -1;
}

// Why lwcport reads a name or path as world-space data.
std::string data_words(const WorldData::Source& s) {
  if (s.by_name) return fmt::format("read as {} by its name (a naming convention lwcport knows)", kind_words(s.kind));
  if (s.pattern.text().size() > 48) return fmt::format("{}, a value lwcport knows", kind_words(s.kind));
  return fmt::format("{}, a value lwcport knows (`{}`)", kind_words(s.kind), s.pattern.text());
}

}  // namespace

Kind value_kind(const WorldModel& model, int node) {
  Kind k = model.kind(node);
  if (k != Kind::unknown || !model.tree().is(node, "identifier")) return k;
  int var = model.variable_declared_at(node);
  if (var < 0) var = model.variable_at(node);
  return var >= 0 ? model.variables()[var].kind : k;
}

ProvenanceTracer::ProvenanceTracer(const WorldModel& model) : m_(model), t_(model.tree()) {
  for (int id : t_.of_type("function_definition")) {
    int name = t_.declarator_name(t_.child_by_field(id, "declarator"));
    if (name >= 0) functions_.emplace(std::string(t_.text(name)), id);
  }
}

std::vector<ProvenanceStep> ProvenanceTracer::trace(int node) {
  steps_.clear();
  seen_.clear();
  // A function's name (a finding on what it returns): from what it returns.
  if (int function = function_named_by(t_, node); function >= 0) {
    node = returned_value(function);
    if (node >= 0) add(node, fmt::format("returns {} (line {})", code(node), line(node)));
  }
  if (node < 0 || !worth_tracing(value_kind(m_, node))) return {};
  for (int hops = 0; node >= 0 && steps_.size() < 8 && hops < 64 && seen_.insert(node).second; ++hops) node = step(node);
  return std::move(steps_);
}

int ProvenanceTracer::line(int node) const { return t_.source->position(t_.at(node).begin).line; }

// A node's text on one line, shortened.
std::string ProvenanceTracer::code(int node) const {
  std::string out;
  for (char c : t_.text(node)) {
    bool blank = c == ' ' || c == '\t' || c == '\r' || c == '\n';
    if (blank && (out.empty() || out.back() == ' ')) continue;
    out += blank ? ' ' : c;
  }
  if (out.size() > 48) out = out.substr(0, 45) + "...";
  return "`" + out + "`";
}

void ProvenanceTracer::add(int node, std::string text) { steps_.push_back({t_.span(node), std::move(text)}); }

// The named child the value most likely came from: the most absolute one.
int ProvenanceTracer::strongest_child(int node) const {
  int best = -1;
  for (int c : t_.named_children(node))
    if (worth_tracing(value_kind(m_, c)) && (best < 0 || concern(value_kind(m_, c)) > concern(value_kind(m_, best)))) best = c;
  return best;
}

const WorldData::Source* ProvenanceTracer::source_for(const Path& path, bool declared_global) const {
  // As the model reads sources: a naming convention counts for a global the file declares, and
  // elsewhere only where names are evidence (plain and UE4-era code).
  bool names = declared_global || m_.names_as_evidence();
  for (const WorldData::Source& s : m_.data().sources)
    if ((!s.by_name || (names && (!s.plain_only || m_.plain_names()))) && s.pattern.matches(path)) return &s;
  return nullptr;
}


// Where a local variable got the value it has at `use`: the last assignment before it that
// carries a traced kind, else its initialiser, else its first such assignment.
int ProvenanceTracer::defining(int var, int use) const {
  const Variable& v = m_.variables()[var];
  // The kind to explain: what the use holds, or, at the declaration, the most absolute it holds.
  Kind wanted = m_.variable_declared_at(use) == var ? v.kind : value_kind(m_, use);
  struct Candidate {
    int node;   // the initialiser or the assignment
    Kind kind;  // what it stores
  };
  std::vector<Candidate> candidates;
  if (v.init >= 0) candidates.push_back({v.init, value_kind(m_, v.init)});
  for (int u : m_.uses(var)) {
    // The store may be to a part of it: `P.xyz -= ..`, `M[3] = ..`.
    int left = u;
    while (t_.at(left).parent >= 0 && (t_.is(t_.at(left).parent, "field_expression") || t_.is(t_.at(left).parent, "subscript_expression")) &&
           t_.child_by_field(t_.at(left).parent, "argument") == left)
      left = t_.at(left).parent;
    int parent = t_.at(left).parent;
    if (parent < 0 || !t_.is(parent, "assignment_expression") || t_.child_by_field(parent, "left") != left) continue;
    candidates.push_back({parent, value_kind(m_, parent)});
  }
  // The last store before the use that gave it this kind; else the last one before it worth
  // tracing; else (a declaration, or a loop) the first store anywhere that gave this kind.
  int same_before = -1, traced_before = -1, same_anywhere = -1;
  for (const Candidate& c : candidates) {
    bool before = t_.at(c.node).end <= t_.at(use).begin;  // the store is complete before the use
    if (c.kind == wanted && before) same_before = c.node;
    if (worth_tracing(c.kind) && before) traced_before = c.node;
    if (c.kind == wanted && same_anywhere < 0) same_anywhere = c.node;
  }
  if (same_before >= 0) return same_before;
  if (m_.variable_declared_at(use) != var && traced_before >= 0) return traced_before;
  return same_anywhere;
}

int ProvenanceTracer::strongest_inside(int node) const {
  int best = -1;
  for (int id = node + 1; id < static_cast<int>(t_.nodes.size()) && t_.at(id).begin < t_.at(node).end; ++id) {
    Kind k = value_kind(m_, id);
    if (worth_tracing(k) && (best < 0 || concern(k) > concern(value_kind(m_, best)))) best = id;
  }
  return best;
}

std::string ProvenanceTracer::return_basis(const std::string& name) const {
  const FileSummary* included = m_.includes();
  if (included && included->function_returns.count(name)) return " (as its definition in an included file does)";
  if (m_.data().engine_functions.count(name)) return " (as Unreal's function of that name does, in lwcport's engine tables)";
  return "";
}

int ProvenanceTracer::argument_for(int var) {
  const Variable& v = m_.variables()[var];
  if (v.function < 0) return -1;
  int name_node = t_.declarator_name(t_.child_by_field(v.function, "declarator"));
  if (name_node < 0) return -1;
  size_t index = 0;
  for (int other = 0; other < var; ++other) {
    const Variable& o = m_.variables()[other];
    index += o.role == Variable::Role::parameter && o.function == v.function;
  }
  if (!calls_) {  // every call of a function by name, built on first use
    calls_.emplace();
    for (int id = 0; id < static_cast<int>(t_.nodes.size()); ++id) {
      int fn = t_.is(id, "call_expression") ? t_.child_by_field(id, "function") : -1;
      if (fn >= 0 && t_.is(fn, "identifier")) (*calls_)[std::string(t_.text(fn))].push_back(id);
    }
  }
  auto calls = calls_->find(t_.text(name_node));
  if (calls == calls_->end()) return -1;
  for (int call : calls->second) {
    int list = t_.child_by_field(call, "arguments");
    std::vector<int> arguments = list >= 0 ? t_.named_children(list) : std::vector<int>{};
    if (index < arguments.size() && value_kind(m_, arguments[index]) == v.kind) return arguments[index];
  }
  return -1;
}

int ProvenanceTracer::returned_value(int function) const {
  int best = -1;
  for (int id = function + 1; id < static_cast<int>(t_.nodes.size()) && t_.at(id).begin < t_.at(function).end; ++id) {
    if (!t_.is(id, "return_statement")) continue;
    int value = t_.named_child(id);
    if (value >= 0 && worth_tracing(value_kind(m_, value)) && (best < 0 || concern(value_kind(m_, value)) > concern(value_kind(m_, best))))
      best = value;
  }
  return best;
}

// Says what happens at `node` (when there is something to say) and returns where its value
// came from, or -1 where the trail ends.
int ProvenanceTracer::step(int node) {
  std::string_view type = t_.at(node).type;
  if (type == "identifier") return step_identifier(node);
  if (type == "field_expression") {
    if (auto path = m_.path(node))
      if (const WorldData::Source* s = source_for(*path)) return add(node, fmt::format("{}: {}", code(node), data_words(*s))), -1;
    int base = t_.child_by_field(node, "argument");
    if (base >= 0 && worth_tracing(value_kind(m_, base))) return base;
    int field = t_.child_by_field(node, "field");
    std::string name = field >= 0 ? std::string(t_.text(field)) : "";
    if (const WorldData::Source* s = source_for(Path{{name, false}})) return add(node, fmt::format("{}: {}", code(node), data_words(*s))), -1;
    // A field of a struct the file declares: what the file stores in it (the model joins every
    // store into a field of that name).
    for (int var = 0; var < static_cast<int>(m_.variables().size()); ++var) {
      const Variable& v = m_.variables()[var];
      if (v.role != Variable::Role::field || v.name != name) continue;
      add(v.declaration >= 0 ? v.declaration : node,
          fmt::format("field `{}.{}` (line {}): {} where the file stores into it", v.owner, name, line(v.declaration >= 0 ? v.declaration : node),
                      kind_words(v.kind)));
      return -1;
    }
    add(node, fmt::format("{} (line {}): {} in Unreal's struct tables or by what the file stores into `{}`", code(node), line(node),
                          kind_words(value_kind(m_, node)), name));
    return -1;
  }
  if (type == "call_expression") {
    int fn = t_.child_by_field(node, "function");
    std::string name = fn >= 0 ? std::string(t_.text(fn)) : "";
    if (auto path = m_.path(node))
      if (const WorldData::Source* s = source_for(*path)) return add(node, fmt::format("{}: {}", code(node), data_words(*s))), -1;
    auto found = fn >= 0 && t_.is(fn, "identifier") ? functions_.find(name) : functions_.end();
    int defined = found != functions_.end() ? found->second : -1;
    if (defined >= 0) {
      add(node, fmt::format("returned by `{}` (line {}, defined at line {})", name, line(node), line(defined)));
      return returned_value(defined);
    }
    int from = t_.child_by_field(node, "arguments");
    int arg = from >= 0 ? strongest_child(from) : -1;
    // A helper that converts or wraps (`DFHackToFloat`, `MakeLWCVector3`) whose direct argument the
    // model left unclassified: the value inside it that is.
    if (arg < 0 && from >= 0) arg = strongest_inside(from);
    if (arg >= 0) {
      add(node, fmt::format("through `{}` (line {})", name, line(node)));
      return arg;
    }
    add(node, fmt::format("`{}` (line {}) returns {}{}", name, line(node), kind_words(value_kind(m_, node)), return_basis(name)));
    return -1;
  }
  if (type == "assignment_expression") return t_.child_by_field(node, "right");
  return strongest_child(node);
}

int ProvenanceTracer::step_identifier(int node) {
  std::string name(t_.text(node));
  int var = m_.variable_at(node);
  if (var < 0) var = m_.variable_declared_at(node);
  if (var < 0) {
    if (const WorldData::Source* s = source_for(Path{{name, false}})) add(node, fmt::format("`{}`: {}", name, data_words(*s)));
    return -1;
  }
  const Variable& v = m_.variables()[var];
  int where = v.declaration >= 0 ? v.declaration : node;
  switch (v.role) {
    case Variable::Role::global: {
      // A global the file writes (a varying, a static) got its value where it was written.
      if (!v.uniform) {
        int from = defining(var, node);
        if (from >= 0 && from != v.init) {
          add(from, fmt::format("{} (line {})", code(from), line(from)));
          return t_.child_by_field(from, "right");
        }
        if (from >= 0) {
          add(where, fmt::format("`{}`, a global initialised at line {}", name, line(where)));
          return v.init;
        }
      }
      const WorldData::Source* s = source_for(Path{{name, false}}, true);
      add(where, s ? fmt::format("`{} {}`, a global (line {}): {}", v.type, name, line(where), data_words(*s))
                   : fmt::format("`{} {}`, a global (line {}): {}", v.type, name, line(where), kind_words(v.kind)));
      return -1;
    }
    case Variable::Role::parameter: {
      int argument = argument_for(var);
      if (argument < 0) {
        add(where, fmt::format("parameter `{}` (line {}): {} where the file calls its function", name, line(where), kind_words(v.kind)));
        return -1;
      }
      add(where, fmt::format("parameter `{}` (line {}), given {} at line {}", name, line(where), code(argument), line(argument)));
      return argument;
    }
    case Variable::Role::field:
      add(where, fmt::format("field `{}.{}` (line {}): {} by what the file assigns to it", v.owner, name, line(where), kind_words(v.kind)));
      return -1;
    case Variable::Role::local: break;
  }
  int from = defining(var, node);
  if (from < 0) return -1;
  if (from == v.init) {
    add(where, fmt::format("`{}` = {} (line {})", name, code(from), line(from)));
    return from;
  }
  int right = t_.child_by_field(from, "right");
  add(from, fmt::format("{} (line {})", code(from), line(from)));
  return right;
}

int value_node_at(const WorldModel& model, uint32_t offset) {
  const SyntaxTree& t = model.tree();
  for (int node = t.deepest_covering(offset, offset); node >= 0 && !ends_a_value(t, node); node = t.at(node).parent)
    if (value_kind(model, node) != Kind::unknown) return node;
  return -1;
}

int value_node_for(const WorldModel& model, Span span) {
  const SyntaxTree& t = model.tree();
  for (int node = t.deepest_covering(span.begin, span.end); node >= 0 && t.span(node) == span; node = t.at(node).parent)
    if (worth_tracing(value_kind(model, node)) || function_named_by(t, node) >= 0) return node;
  return -1;
}

}  // namespace lwc
