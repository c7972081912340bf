#include "lang/syntax.h"

#include <algorithm>

#include "lang/formats.h"

#include <tree_sitter/api.h>

#include <cstring>
#include <memory>


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

void flatten(TSTree* tree, SyntaxTree& out) {
  TSTreeCursor cursor = ts_tree_cursor_new(ts_tree_root_node(tree));
  std::vector<int32_t> parents;        // ids of the open ancestors
  std::vector<int32_t> last_child;     // per node id, its last child so far
  auto add = [&]() -> int32_t {
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
    node.parent = parents.empty() ? -1 : parents.back();
    node.depth = static_cast<uint32_t>(parents.size());
    int32_t id = static_cast<int32_t>(out.nodes.size());
    if (node.error) {
      if (out.error_count++ == 0) out.first_error = node.begin;
    }
    if (node.parent >= 0) {
      int32_t& last = last_child[node.parent];
      if (last < 0) out.nodes[node.parent].first_child = id;
      else out.nodes[last].next_sibling = id;
      last = id;
    }
    out.nodes.push_back(node);
    last_child.push_back(-1);
    return id;
  };
  int32_t current = add();
  for (;;) {
    if (ts_tree_cursor_goto_first_child(&cursor)) {
      parents.push_back(current);
      current = add();
      continue;
    }
    while (!ts_tree_cursor_goto_next_sibling(&cursor)) {
      if (!ts_tree_cursor_goto_parent(&cursor)) {
        ts_tree_cursor_delete(&cursor);
        return;
      }
      parents.pop_back();
    }
    current = add();
  }
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
  TSParser* parser = thread_parser(lang);
  ts_parser_set_timeout_micros(parser, static_cast<uint64_t>(std::max(1e-6, options.max_parse_seconds) * 1e6));
  ParseReuse::Last* last = options.reuse ? &options.reuse->last_[{lang, options.variant}] : nullptr;
  if (last && last->tree) {
    TSInputEdit edit = edit_between(last->masked, masked.text);
    ts_tree_edit(last->tree, &edit);
  }
  std::unique_ptr<TSTree, TreeDeleter> tree(
      ts_parser_parse_string(parser, last ? last->tree : nullptr, masked.text.data(), static_cast<uint32_t>(masked.text.size())));
  if (last && last->tree) {
    ts_tree_delete(last->tree);  // edited: good for nothing but this parse
    last->tree = nullptr;
  }
  if (!tree) {  // out of budget: the parser keeps its state for a resume that will not come
    ts_parser_reset(parser);
    out.timed_out = true;
    return out;
  }
  flatten(tree.get(), out);
  if (last) {
    last->tree = tree.release();
    last->masked = std::move(masked.text);
  }
  return out;
}

}  // namespace lwc
