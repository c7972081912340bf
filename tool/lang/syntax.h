#pragma once
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/source.h"
#include "lang/mask.h"

struct TSTree;

namespace lwc {

enum class Lang { hlsl, glsl };
std::string_view lang_name(Lang lang);
std::optional<Lang> parse_lang(std::string_view name);
// The language of a path by the default extensions (lang/formats.h); GLSL for a script.
std::optional<Lang> lang_from_path(std::string_view path);

// One tree-sitter node, flattened: the tree is a pre-order array so analyses walk it without
// recursion (10,000 nested parentheses are fine) and the tree-sitter tree is freed after parsing.
// `name` equals the grammar's C string `s`, without measuring `s` first (the hottest comparison).
inline bool names_equal(std::string_view name, const char* s) {
  for (char c : name)
    if (*s++ != c) return false;
  return *s == '\0';
}

struct Node {
  const char* type = "";      // tree-sitter node type (a static string of the grammar)
  const char* field = nullptr;  // field name in the parent, if any
  uint32_t begin = 0, end = 0;
  int32_t parent = -1, first_child = -1, next_sibling = -1;
  uint32_t depth = 0;
  bool named = false;
  bool error = false;  // an ERROR node or a MISSING token
};

class SyntaxTree {
 public:
  Lang lang = Lang::hlsl;
  const Source* source = nullptr;
  std::vector<Node> nodes;  // nodes[0] is the root
  int error_count = 0;
  uint32_t first_error = 0;
  std::optional<uint32_t> unterminated_comment;  // offset of a `/*` that never ends
  bool timed_out = false;  // the parser ran out of its budget (MaskOptions::max_parse_seconds): no nodes
  int variants = 1;  // how many variants the file's preprocessor groups need (lang/conditionals.h)
  std::vector<Span> resolved_conditionals;  // groups resolved per variant: no rewrite touches them
  std::vector<Span> kept_arms;              // the arms of them this variant keeps (where variants differ)
  // A parse that edited the document's last one (ParseReuse): its number, the last one's, and
  // the top-level declarations it copied from there unchanged (their first node here and there,
  // and how many nodes each has). Analyses of the last tree can keep what they found there.
  struct Reused {
    int32_t here, there, count;
  };
  uint64_t number = 0, reused_from = 0;
  std::vector<Reused> reused;

  const Node& at(int id) const { return nodes[id]; }
  bool is(int id, std::string_view type) const { return id >= 0 && names_equal(type, nodes[id].type); }
  std::string_view text(int id) const;
  Span span(int id) const { return {nodes[id].begin, nodes[id].end}; }
  int child_by_field(int id, std::string_view field) const;
  // The first named child, or the n-th named child.
  int named_child(int id, int n = 0) const;
  std::vector<int> named_children(int id) const;
  // Every node of a type, in pre-order (source order); each type is found once per tree, as
  // several checks ask for the same one.
  const std::vector<int>& of_type(std::string_view type) const;
  // The deepest node whose span holds [begin, end] (of the children that hold it, the first with
  // any width), or -1 in an empty tree.
  int deepest_covering(uint32_t begin, uint32_t end) const;
  // Nearest ancestor (or self) of the given type, or -1.
  int ancestor(int id, std::string_view type) const;
  // The identifier a declarator declares (through arrays, pointers, references, initialisers,
  // function declarators), or -1.
  int declarator_name(int declarator) const;
  // The index expression of a subscript (`M[3]`: the `3`), in both grammars, or -1.
  int subscript_index(int subscript) const;
  // `(float3x3)(X)`: a cast whose operand is parenthesised is parsed as a call of the parenthesised
  // type name. That name's node when `call` is such a call with one argument, else -1 (the caller
  // decides whether the name is a type).
  int cast_written_as_call(int call) const;
  // Function definitions and calls by their plain name (an identifier), and whether any identifier
  // is spelled so: indexed on first use, as the checks ask once per finding (a scan of the whole
  // tree each time made lint quadratic in the file's size).
  const std::vector<int>& definitions_named(std::string_view name) const;
  const std::vector<int>& calls_named(std::string_view name) const;
  bool has_identifier(std::string_view name) const;

 private:
  void index_names() const;
  mutable bool names_indexed_ = false;
  mutable std::map<std::string_view, std::vector<int>, std::less<>> definitions_by_name_, calls_by_name_;
  mutable std::set<std::string_view, std::less<>> identifiers_;
  mutable std::vector<std::pair<const char*, std::vector<int>>> by_type_pointer_;  // every node, by its type's string
  mutable std::deque<std::pair<std::string, std::vector<int>>> of_type_;  // a deque: what of_type returned stays put
};

// The tree-sitter trees of one document's last parse (per language and variant), kept so that the
// next parse of its edited text is tree-sitter's incremental one: the old tree is edited where the
// text changed and only what the edit touches is parsed again; a declaration of the file outside
// what tree-sitter reports changed is copied from the last flattening, not walked again. Text with
// a syntax error is parsed afresh (tree-sitter's recovery can differ between the two). For an
// editor's open documents; the result is the tree a fresh parse gives.
class ParseReuse {
 public:
  ParseReuse() = default;
  ParseReuse(const ParseReuse&) = delete;
  ParseReuse& operator=(const ParseReuse&) = delete;
  ~ParseReuse();

  // A flattening (SyntaxTree::nodes) and where each top-level node starts in it.
  struct Flat {
    struct Top {
      int32_t first, count;  // a declaration's first node and how many nodes it has
    };
    std::vector<Node> nodes;
    std::vector<Top> tops;
    uint64_t number = 0;  // SyntaxTree::number
  };

 private:
  friend SyntaxTree parse(const Source& source, Lang lang, const MaskOptions& options);
  struct Last {
    std::string masked;   // the text the tree was parsed from
    TSTree* tree = nullptr;
    Flat flat;            // the tree flattened
  };
  std::map<std::pair<Lang, int>, Last> last_;
};

// Parses one variant of a source in the given language, after masking (lang/mask.h): HLSL with
// the C++ grammar, GLSL with its own; byte offsets always match the original text.
SyntaxTree parse(const Source& source, Lang lang, const MaskOptions& options = {});

}  // namespace lwc
