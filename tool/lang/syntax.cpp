#include "lang/syntax.h"

#include <algorithm>

#include "lang/formats.h"

#include <tree_sitter/api.h>

#include <atomic>
#include <cstring>
#include <iterator>
#include <optional>
#include <memory>
#include <unordered_map>


extern "C" const TSLanguage* tree_sitter_cpp(void);
extern "C" const TSLanguage* tree_sitter_glsl(void);

namespace lwc {

std::string_view lang_name(Lang lang) { return lang == Lang::hlsl ? "hlsl" : "glsl"; }

std::optional<Lang> parse_lang(std::string_view name) {
  if (name == "hlsl") return Lang::hlsl;
  if (name == "glsl") return Lang::glsl;
  return std::nullopt;
}

std::optional<Lang> lang_from_path(std::string_view path) {
  auto format = FormatTable::defaults().for_path(path);
  return format ? std::optional<Lang>(format->lang) : std::nullopt;
}

// No node (-1, a field the parser left out under error recovery) has no text.
std::string_view SyntaxTree::text(int id) const { return id < 0 ? std::string_view() : source->slice(span(id)); }

int SyntaxTree::child_by_field(int id, std::string_view field) const {
  for (int c = nodes[id].first_child; c >= 0; c = nodes[c].next_sibling)
    if (nodes[c].field && names_equal(field, nodes[c].field)) return c;
  return -1;
}

int SyntaxTree::named_child(int id, int n) const {
  for (int c = nodes[id].first_child; c >= 0; c = nodes[c].next_sibling)
    if (nodes[c].named && n-- == 0) return c;
  return -1;
}

std::vector<int> SyntaxTree::named_children(int id) const {
  std::vector<int> out;
  for (int c = nodes[id].first_child; c >= 0; c = nodes[c].next_sibling)
    if (nodes[c].named) out.push_back(c);
  return out;
}

void SyntaxTree::index_names() const {
  if (names_indexed_) return;
  names_indexed_ = true;
  for (int id : of_type("identifier")) identifiers_.insert(text(id));
  for (int fn : of_type("function_definition")) {
    int declarator = child_by_field(fn, "declarator");
    int name = declarator >= 0 ? child_by_field(declarator, "declarator") : -1;
    if (name >= 0 && is(name, "identifier")) definitions_by_name_[text(name)].push_back(fn);
  }
  for (int call : of_type("call_expression")) {
    int name = child_by_field(call, "function");
    if (name >= 0 && is(name, "identifier")) calls_by_name_[text(name)].push_back(call);
  }
}

const std::vector<int>& SyntaxTree::definitions_named(std::string_view name) const {
  static const std::vector<int> none;
  index_names();
  auto it = definitions_by_name_.find(name);
  return it != definitions_by_name_.end() ? it->second : none;
}

const std::vector<int>& SyntaxTree::calls_named(std::string_view name) const {
  static const std::vector<int> none;
  index_names();
  auto it = calls_by_name_.find(name);
  return it != calls_by_name_.end() ? it->second : none;
}

bool SyntaxTree::has_identifier(std::string_view name) const {
  index_names();
  return identifiers_.count(name) > 0;
}

const std::vector<int>& SyntaxTree::of_type(std::string_view type) const {
  if (by_type_pointer_.empty() && !nodes.empty()) {
    // One pass for every type: a node's type is one of the grammar's static strings.
    std::unordered_map<const char*, std::vector<int>> index;
    const char* last = nullptr;
    std::vector<int>* list = nullptr;
    for (int id = 0; id < static_cast<int>(nodes.size()); ++id) {
      if (nodes[id].type != last) list = &index[last = nodes[id].type];
      list->push_back(id);
    }
    by_type_pointer_.assign(std::make_move_iterator(index.begin()), std::make_move_iterator(index.end()));
  }
  for (const auto& [name, ids] : of_type_)
    if (name == type) return ids;
  // An alias can give one name two strings of the grammar: their nodes are merged in order.
  std::vector<int> ids;
  for (const auto& [pointer, list] : by_type_pointer_) {
    if (!names_equal(type, pointer)) continue;
    std::vector<int> merged;
    std::merge(ids.begin(), ids.end(), list.begin(), list.end(), std::back_inserter(merged));
    ids = std::move(merged);
  }
  return of_type_.emplace_back(std::string(type), std::move(ids)).second;
}

int SyntaxTree::deepest_covering(uint32_t begin, uint32_t end) const {
  if (nodes.empty()) return -1;
  auto holds = [&](int n) { return nodes[n].begin <= begin && end <= nodes[n].end && nodes[n].end > nodes[n].begin; };
  int node = 0;
  if (begin < end) {
    // Nodes are in pre-order, so the last one to begin by `begin` lies inside the deepest that
    // holds the span: up from it is a holder (a wide span has one chain of holders, and the
    // descent below finds the deepest) without walking the thousand declarations of a file.
    auto after = std::upper_bound(nodes.begin(), nodes.end(), begin, [](uint32_t at, const Node& n) { return at < n.begin; });
    for (node = static_cast<int>(after - nodes.begin()) - 1; node > 0 && !holds(node);) node = nodes[node].parent;
    node = std::max(node, 0);
  }
  for (bool deeper = true; deeper;) {
    deeper = false;
    for (int c = nodes[node].first_child; c >= 0; c = nodes[c].next_sibling) {
      if (holds(c)) {
        node = c;
        deeper = true;
        break;
      }
    }
  }
  return node;
}

int SyntaxTree::ancestor(int id, std::string_view type) const {
  for (; id >= 0; id = nodes[id].parent)
    if (names_equal(type, nodes[id].type)) return id;
  return -1;
}

int SyntaxTree::declarator_name(int d) const {
  while (d >= 0) {
    std::string_view type = nodes[d].type;
    if (type == "identifier" || type == "field_identifier") return d;
    int inner = child_by_field(d, "declarator");
    d = inner >= 0 ? inner : named_child(d);
  }
  return -1;
}

int SyntaxTree::subscript_index(int subscript) const {
  int index = child_by_field(subscript, "index");  // GLSL
  if (index >= 0) return index;
  int list = child_by_field(subscript, "indices");  // the C++ grammar: a subscript_argument_list
  return list >= 0 ? named_child(list) : -1;
}

int SyntaxTree::cast_written_as_call(int call) const {
  if (!is(call, "call_expression")) return -1;
  int fn = child_by_field(call, "function");
  int args = child_by_field(call, "arguments");
  if (!is(fn, "parenthesized_expression") || args < 0 || named_children(fn).size() != 1 || named_children(args).size() != 1)
    return -1;
  int type = named_child(fn);
  return is(type, "identifier") || is(type, "type_identifier") || is(type, "primitive_type") ? type : -1;
}

namespace {

struct ParserDeleter {
  void operator()(TSParser* p) const { ts_parser_delete(p); }
};
struct TreeDeleter {
  void operator()(TSTree* t) const { ts_tree_delete(t); }
};

// One parser per thread and language: creating one costs more than parsing a small file.
TSParser* thread_parser(Lang lang) {
  thread_local std::unique_ptr<TSParser, ParserDeleter> parsers[2];
  auto& p = parsers[lang == Lang::hlsl ? 0 : 1];
  if (!p) {
    p.reset(ts_parser_new());
    ts_parser_set_language(p.get(), lang == Lang::hlsl ? tree_sitter_cpp() : tree_sitter_glsl());
  }
  return p.get();
}

// Punctuation tokens carry nothing the analyses read (their parent's span and fields say it all)
// and are a third of all nodes, so they are not copied; a MISSING one is, as an error.
bool is_punctuation(const char* type) {
  for (const char* c = type; *c; ++c)
    if (!std::strchr("(){}[];,", *c)) return false;
  return *type != 0;
}

// Builds the flattened tree in pre-order, from tree-sitter's nodes or, for a declaration no change
// touched, from the last parse's flattening.
class Flattener {
 public:
  explicit Flattener(SyntaxTree& out) : out_(out) {}

  // Appends the node under the cursor and everything below it.
  void walk(TSTreeCursor& cursor, int32_t parent) {
    int32_t current = add(cursor, parent);
    std::vector<int32_t> parents;  // the open ancestors below the starting node
    for (;;) {
      if (ts_tree_cursor_goto_first_child(&cursor)) {
        parents.push_back(current);
        current = add(cursor, parents.back());
        continue;
      }
      for (;;) {
        if (parents.empty()) return;  // never past the starting node
        if (ts_tree_cursor_goto_next_sibling(&cursor)) break;
        ts_tree_cursor_goto_parent(&cursor);
        parents.pop_back();
      }
      current = add(cursor, parents.back());
    }
  }

  // Appends the node under the cursor alone (-1 for punctuation, which is not kept).
  int32_t add(TSTreeCursor& cursor, int32_t parent) {
    TSNode n = ts_tree_cursor_current_node(&cursor);
    Node node;
    node.type = ts_node_type(n);
    node.named = ts_node_is_named(n);
    bool missing = ts_node_is_missing(n);
    if (!node.named && !missing && is_punctuation(node.type)) return -1;
    node.field = ts_tree_cursor_current_field_name(&cursor);
    node.begin = ts_node_start_byte(n);
    node.end = ts_node_end_byte(n);
    node.error = missing || (ts_node_symbol(n) == static_cast<TSSymbol>(-1));
    node.parent = parent;
    node.depth = parent < 0 ? 0 : out_.nodes[parent].depth + 1;
    auto id = static_cast<int32_t>(out_.nodes.size());
    append(node);
    link(parent, id);
    return id;
  }

  // Appends `count` nodes of an earlier flattening from `first` (a whole subtree), moved by
  // `shift` bytes, as a child of `parent`.
  void copy(const std::vector<Node>& from, int32_t first, int32_t count, int64_t shift, int32_t parent, const char* field) {
    auto base = static_cast<int32_t>(out_.nodes.size());
    auto moved = [&](int32_t id) { return id < 0 ? -1 : id - first + base; };
    // The same declaration can sit at another depth now (an #if line around it typed or deleted).
    int64_t deeper = int64_t{parent < 0 ? 0 : out_.nodes[parent].depth + 1} - from[first].depth;
    for (int32_t k = first; k < first + count; ++k) {
      Node n = from[k];
      n.begin = static_cast<uint32_t>(n.begin + shift);
      n.end = static_cast<uint32_t>(n.end + shift);
      n.depth = static_cast<uint32_t>(n.depth + deeper);
      n.first_child = moved(n.first_child);
      n.next_sibling = k == first ? -1 : moved(n.next_sibling);
      n.parent = k == first ? parent : moved(n.parent);
      if (k == first) n.field = field;
      append(n);
    }
    link(parent, base);
  }

 private:
  void append(const Node& node) {
    if (node.error && out_.error_count++ == 0) out_.first_error = node.begin;
    out_.nodes.push_back(node);
    last_child_.push_back(-1);
  }

  void link(int32_t parent, int32_t id) {
    if (parent < 0) return;
    int32_t& last = last_child_[parent];
    if (last < 0) out_.nodes[parent].first_child = id;
    else out_.nodes[last].next_sibling = id;
    last = id;
  }

  SyntaxTree& out_;
  std::vector<int32_t> last_child_;  // per node id, its last child so far
};

// Where a new tree can differ from the last one: tree-sitter's changed ranges and the edited
// text, in the new text's bytes, and how the edit moved what follows it.
struct Changes {
  std::vector<std::pair<uint32_t, uint32_t>> ranges;
  TSInputEdit edit;

  bool touch(uint32_t begin, uint32_t end) const {
    return std::any_of(ranges.begin(), ranges.end(), [&](auto r) { return r.first <= end && begin <= r.second; });
  }
  // Where a byte of the new text outside the edit was in the last text.
  int64_t before(uint32_t at) const {
    return at >= edit.new_end_byte ? int64_t{at} - edit.new_end_byte + edit.old_end_byte : at;
  }
};

// Preprocessor groups and blocks (`#if` arms, a masked cbuffer's `extern "C" { }`) hold
// declarations as the file does: their children are reused one by one, to this depth.
bool holds_declarations(const char* type) {
  for (const char* t : {"preproc_if", "preproc_ifdef", "preproc_else", "preproc_elif", "linkage_specification", "declaration_list"})
    if (std::strcmp(type, t) == 0) return true;
  return false;
}
constexpr int kReuseDepth = 8;

// Flattens `tree`. With `last` (the document's last flattening of this variant) and the changes
// since, a declaration of the file (at the top level, or in a group or block that holds
// declarations) no change touches keeps the structure it had, and is copied from the last
// flattening rather than walked again; `last` then describes this flattening.
void flatten(TSTree* tree, SyntaxTree& out, ParseReuse::Flat* last, const Changes* changes) {
  Flattener flat(out);
  TSTreeCursor cursor = ts_tree_cursor_new(ts_tree_root_node(tree));
  if (!last) {
    flat.walk(cursor, -1);
    ts_tree_cursor_delete(&cursor);
    return;
  }
  auto key = [](int64_t begin, int64_t end) { return (begin << 32) | end; };
  std::unordered_map<int64_t, const ParseReuse::Flat::Top*> earlier;  // by first and last byte
  if (changes)
    for (const auto& top : last->tops) earlier.emplace(key(last->nodes[top.first].begin, last->nodes[top.first].end), &top);
  std::vector<ParseReuse::Flat::Top> tops;
  // The children of the node under the cursor, each copied or walked (or, for a group that holds
  // declarations, added and its children done alike); the cursor ends where it started.
  auto children = [&](auto& self, int32_t parent, int depth) -> void {
    for (bool more = ts_tree_cursor_goto_first_child(&cursor); more; more = ts_tree_cursor_goto_next_sibling(&cursor)) {
      TSNode n = ts_tree_cursor_current_node(&cursor);
      uint32_t begin = ts_node_start_byte(n), end = ts_node_end_byte(n);
      auto first = static_cast<int32_t>(out.nodes.size());
      auto it = changes && !changes->touch(begin, end) ? earlier.find(key(changes->before(begin), changes->before(end))) : earlier.end();
      const ParseReuse::Flat::Top* old = it != earlier.end() ? it->second : nullptr;
      if (old && names_equal(last->nodes[old->first].type, ts_node_type(n))) {
        flat.copy(last->nodes, old->first, old->count, int64_t{begin} - last->nodes[old->first].begin, parent,
                  ts_tree_cursor_current_field_name(&cursor));
        out.reused.push_back({first, old->first, old->count});
      } else if (depth < kReuseDepth && holds_declarations(ts_node_type(n))) {
        int32_t group = flat.add(cursor, parent);
        self(self, group, depth + 1);
      } else {
        flat.walk(cursor, parent);
      }
      auto count = static_cast<int32_t>(out.nodes.size()) - first;
      if (count > 0) tops.push_back({first, count});
    }
    ts_tree_cursor_goto_parent(&cursor);
  };
  int32_t root = flat.add(cursor, -1);
  children(children, root, 0);
  ts_tree_cursor_delete(&cursor);
  static std::atomic<uint64_t> parses{0};
  out.reused_from = last->number;
  out.number = last->number = ++parses;
  last->tops = std::move(tops);
  last->nodes = out.nodes;
}

// The row and byte column `to` is at in `text`, counting on from `from` at `p`.
TSPoint advance(std::string_view text, size_t from, TSPoint p, size_t to) {
  std::string_view part = text.substr(from, to - from);
  size_t last_line = part.rfind('\n');
  if (last_line == std::string_view::npos) return {p.row, p.column + static_cast<uint32_t>(part.size())};
  return {p.row + static_cast<uint32_t>(std::count(part.begin(), part.end(), '\n')), static_cast<uint32_t>(part.size() - last_line - 1)};
}

// The one edit that turns `before` into `after`: what lies between their common start and end.
TSInputEdit edit_between(std::string_view before, std::string_view after) {
  size_t start = 0, shorter = std::min(before.size(), after.size());
  while (start < shorter && before[start] == after[start]) ++start;
  size_t tail = 0;
  while (tail < shorter - start && before[before.size() - 1 - tail] == after[after.size() - 1 - tail]) ++tail;
  TSInputEdit e;
  e.start_byte = static_cast<uint32_t>(start);
  e.old_end_byte = static_cast<uint32_t>(before.size() - tail);
  e.new_end_byte = static_cast<uint32_t>(after.size() - tail);
  e.start_point = advance(before, 0, {0, 0}, start);  // the texts agree up to `start`
  e.old_end_point = advance(before, start, e.start_point, e.old_end_byte);
  e.new_end_point = advance(after, start, e.start_point, e.new_end_byte);
  return e;
}

}  // namespace

ParseReuse::~ParseReuse() {
  for (auto& [key, last] : last_)
    if (last.tree) ts_tree_delete(last.tree);
}

SyntaxTree parse(const Source& source, Lang lang, const MaskOptions& options) {
  SyntaxTree out;
  out.lang = lang;
  out.source = &source;
  MaskResult masked = mask_source(source.text(), lang, options);
  out.unterminated_comment = masked.unterminated_comment;
  out.variants = masked.variants;
  out.resolved_conditionals = std::move(masked.resolved_conditionals);
  out.kept_arms = std::move(masked.kept_arms);
  TSParser* parser = thread_parser(lang);
  ts_parser_set_timeout_micros(parser, static_cast<uint64_t>(std::max(1e-6, options.max_parse_seconds) * 1e6));
  ParseReuse::Last* last = options.reuse ? &options.reuse->last_[{lang, options.variant}] : nullptr;
  // Where the text has a syntax error, an incremental parse can recover from it otherwise than a
  // fresh one does (seen on Unreal's shaders): a tree with an error is neither edited nor kept
  // as one, and text with an error is parsed afresh.
  std::optional<Changes> changes;
  if (last && last->tree && !ts_node_has_error(ts_tree_root_node(last->tree))) {
    changes.emplace();
    changes->edit = edit_between(last->masked, masked.text);
    ts_tree_edit(last->tree, &changes->edit);
  }
  std::unique_ptr<TSTree, TreeDeleter> tree(
      ts_parser_parse_string(parser, changes ? last->tree : nullptr, masked.text.data(), static_cast<uint32_t>(masked.text.size())));
  bool broken = tree && ts_node_has_error(ts_tree_root_node(tree.get()));
  if (broken && changes) {
    changes.reset();
    tree.reset(ts_parser_parse_string(parser, nullptr, masked.text.data(), static_cast<uint32_t>(masked.text.size())));
  }
  if (!tree) {  // out of budget: the parser keeps its state for a resume that will not come
    ts_parser_reset(parser);
    out.timed_out = true;
    if (last && last->tree) {
      ts_tree_delete(last->tree);
      last->tree = nullptr;
      last->flat = {};
    }
    return out;
  }
  if (changes) {
    uint32_t count = 0;
    TSRange* ranges = ts_tree_get_changed_ranges(last->tree, tree.get(), &count);
    for (uint32_t i = 0; i < count; ++i) changes->ranges.emplace_back(ranges[i].start_byte, ranges[i].end_byte);
    free(ranges);
    changes->ranges.emplace_back(changes->edit.start_byte, changes->edit.new_end_byte);
  }
  if (broken && last) last->flat = {};
  flatten(tree.get(), out, last && !broken ? &last->flat : nullptr, changes ? &*changes : nullptr);
  if (last) {
    if (last->tree) ts_tree_delete(last->tree);
    last->tree = tree.release();
    last->masked = std::move(masked.text);
  }
  return out;
}

}  // namespace lwc
