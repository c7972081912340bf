#include "verify/kernel_builder.h"

#include <fmt/format.h>

#include <charconv>

#include <functional>
#include <map>
#include <optional>
#include <set>

#include "lang/mask.h"
#include "lang/tokens.h"
#include "verify/double_intrinsics.h"

namespace lwc {

namespace {

struct Field {
  std::string type, name, semantic;
};
using Structs = std::map<std::string, std::vector<Field>>;

// Text between top-level items that belongs to no item of its own: white space, and the `;`
// that ends a struct definition (the grammar leaves it outside the struct's node).
bool blank(std::string_view s) { return s.find_first_not_of(" \t\r\n;") == std::string_view::npos; }

bool is_line_directive(std::string_view item) {
  size_t at = item.find_first_not_of(" \t");
  if (at == std::string_view::npos || item[at] != '#') return false;
  at = item.find_first_not_of(" \t", at + 1);
  return at != std::string_view::npos && item.substr(at, 4) == "line";
}


// Where each offset of a preprocessed HLSL text came from, by the `#line` directives the includer
// writes around every include: the cut-down kernel carries one before each item it keeps, so its
// messages name the real file and line.
class LineMap {
 public:
  explicit LineMap(std::string_view text) : text_(text) {
    for (size_t begin = 0; begin < text.size();) {
      size_t end = std::min(text.find('\n', begin), text.size());
      std::string_view line = text.substr(begin, end - begin);
      if (is_line_directive(line)) {
        // `#line N` or `#line N "file"`
        std::string_view rest = line.substr(line.find("line") + 4);
        rest.remove_prefix(std::min(rest.size(), rest.find_first_not_of(" \t")));
        int number = 0;
        auto [digits_end, error] = std::from_chars(rest.data(), rest.data() + rest.size(), number);
        if (error == std::errc()) {
          rest = rest.substr(static_cast<size_t>(digits_end - rest.data()));
          size_t open = rest.find('"'), close = rest.rfind('"');
          std::string file = open != close ? std::string(rest.substr(open + 1, close - open - 1))
                             : marks_.empty() ? std::string() : marks_.back().file;
          marks_.push_back({std::min(end + 1, text.size()), number, file});
        }
      }
      begin = end + 1;
    }
  }
  // `#line N "file"` naming where the line holding `offset` came from; "" when nothing says.
  std::string directive(size_t offset) const {
    auto after = std::upper_bound(marks_.begin(), marks_.end(), offset, [](size_t o, const Mark& m) { return o < m.after; });
    if (after == marks_.begin()) return "";
    const Mark& m = *std::prev(after);
    size_t line_begin = text_.rfind('\n', offset == 0 ? 0 : offset - 1);
    line_begin = offset == 0 || line_begin == std::string_view::npos ? 0 : line_begin + 1;
    long lines = line_begin > m.after ? std::count(text_.begin() + static_cast<long>(m.after), text_.begin() + static_cast<long>(line_begin), '\n') : 0;
    return fmt::format("#line {} \"{}\"\n", m.line + lines, m.file);
  }
  bool empty() const { return marks_.empty(); }

 private:
  struct Mark {
    size_t after;  // the offset of the line after the directive
    int line;
    std::string file;
  };
  std::string_view text_;
  std::vector<Mark> marks_;
};

// The fields one declaration in a struct body declares (`float3 a, b[2] : TEXCOORD0`), from the
// tokens [from, to) of the body; declarators the harness cannot read are left out.
void read_fields(const TokenText& t, size_t from, size_t to, std::vector<Field>& fields) {
  static const std::set<std::string_view> qualifiers = {"precise", "nointerpolation", "linear", "centroid", "noperspective",
                                                        "sample", "flat", "smooth", "highp", "mediump", "lowp"};
  size_t i = from;
  while (i < to && t.ident(i) && qualifiers.count(t[i])) ++i;
  if (i + 1 >= to || !t.ident(i)) return;
  std::string type(t[i++]);
  while (i < to) {
    size_t end = i;  // this declarator: up to the next comma
    while (end < to && t[end] != ",") ++end;
    Field f{type, std::string(t[i]), ""};
    size_t k = i + 1;
    if (k < end && t[k] == "[") {
      f.type += '[';
      for (++k; k < end && t[k] != "]"; ++k) f.type += t[k];
      f.type += ']';
      ++k;
    }
    if (k + 1 < end && t[k] == ":" && t.ident(k + 1)) {
      f.semantic = t[k + 1];
      k += 2;
    }
    if (t.ident(i) && k == end) fields.push_back(f);
    i = end + 1;
  }
}

// Struct definitions of a preprocessed text (macros already expanded).
Structs read_structs(std::string_view text) {
  Structs out;
  TokenText t(text);
  for (size_t i = 0; i < t.size(); ++i) {
    if (!t.spells(i, {"struct", "", "{"})) continue;
    size_t close = i + 3;
    while (close < t.size() && t[close] != "}") ++close;
    std::vector<Field>& fields = out[std::string(t[i + 1])];
    for (size_t start = i + 3, k = start; k < close; ++k)
      if (t[k] == ";") {
        read_fields(t, start, k, fields);
        start = k + 1;
      }
    i = close;
  }
  return out;
}

// float, float3, float4x4, vec3, mat4, mat4x3, int, uint2, bool, double3, dmat4...: rows and
// columns as stored (HLSL: rows x columns; GLSL: columns x rows), 0 when not a basic type.
struct Basic {
  int a = 0, b = 1;  // HLSL: a rows, b columns; GLSL matrices: a columns, b rows; vectors: a
  bool matrix = false, integer = false;
  int count() const { return a * b; }
};
// The size digit at `s[i]` when it is in [low, 4], else 0.
int size_digit(std::string_view s, size_t i, char low) { return i < s.size() && s[i] >= low && s[i] <= '4' ? s[i] - '0' : 0; }
Basic basic_type(std::string_view type) {
  for (std::string_view scalar : {"float", "half", "double", "min16float", "int", "uint", "bool", "dword"}) {
    if (!type.starts_with(scalar)) continue;
    std::string_view rest = type.substr(scalar.size());
    Basic b;
    b.integer = scalar == "int" || scalar == "uint" || scalar == "bool" || scalar == "dword";
    int rows = size_digit(rest, 0, '1'), columns = size_digit(rest, 2, '1');
    if (rest.empty()) b.a = 1;
    else if (rows && rest.size() == 1) b.a = rows;
    else if (rows && columns && rest.size() == 3 && rest[1] == 'x') b = {rows, columns, true, b.integer};
    return b;
  }
  std::string_view glsl = type;
  bool float64 = glsl.starts_with('d'), integer = glsl.starts_with('b') || glsl.starts_with('i') || glsl.starts_with('u');
  if (float64 || integer) glsl.remove_prefix(1);
  if (glsl.starts_with("vec") && glsl.size() == 4 && size_digit(glsl, 3, '2')) return {size_digit(glsl, 3, '2'), 1, false, integer};
  if (integer || !glsl.starts_with("mat")) return {};
  int columns = size_digit(glsl, 3, '2'), rows = size_digit(glsl, 5, '2');
  if (columns && glsl.size() == 4) return {columns, columns, true, false};
  if (columns && rows && glsl.size() == 6 && glsl[4] == 'x') return {columns, rows, true, false};
  return {};
}

std::optional<std::pair<Encoding, int>> special_encoding(const std::string& type) {
  static const std::map<std::string, std::pair<Encoding, int>> table = {
      {"FDFScalar", {Encoding::df, 1}},        {"FDFVector2", {Encoding::df, 2}},
      {"FDFVector3", {Encoding::df, 3}},       {"FDFVector4", {Encoding::df, 4}},
      {"FLWCScalar", {Encoding::lwc, 1}},      {"FLWCVector2", {Encoding::lwc, 2}},
      {"FLWCVector3", {Encoding::lwc, 3}},     {"FLWCVector4", {Encoding::lwc, 4}},
      {"FDFMatrix", {Encoding::df_matrix, 16}}, {"FDFInverseMatrix", {Encoding::df_inverse_matrix, 16}},
      {"FLWCMatrix", {Encoding::lwc_matrix, 16}}, {"FLWCInverseMatrix", {Encoding::lwc_inverse_matrix, 16}},
  };
  auto it = table.find(type);
  if (it == table.end()) return std::nullopt;
  return it->second;
}

// Leaves of a value of `type` at `path`; false when some part cannot be filled (arrays, unknown types).
bool collect_leaves(const Structs& structs, const std::string& type, const std::string& path, const std::string& name,
                    const std::string& semantic, std::vector<Leaf>& out, int& offset, int depth = 0) {
  if (depth > 8) return false;
  if (size_t bracket = type.find('['); bracket != std::string::npos) {
    // A fixed-size array, element by element; a runtime-sized one (`T x[]`) has one element here.
    std::string count = type.substr(bracket + 1, type.find(']') - bracket - 1);
    int n = count.empty() ? 1 : std::atoi(count.c_str());
    if (n < 1 || n > 64) return false;
    std::string element = type.substr(0, bracket) + type.substr(type.find(']') + 1);  // `T[4]` of `T[2][4]`
    for (int i = 0; i < n; ++i)
      if (!collect_leaves(structs, element, fmt::format("{}[{}]", path, i), name, semantic, out, offset, depth + 1))
        return false;
    return true;
  }
  Leaf leaf{path, name, type, semantic, {}};
  if (auto special = special_encoding(type)) {
    leaf.encoding = special->first;
    leaf.components = special->second;
    leaf.width = leaf.encoding == Encoding::df || leaf.encoding == Encoding::lwc ? 2 * leaf.components : 16 + 3;
  } else if (Basic b = basic_type(type); b.count()) {
    leaf.components = leaf.width = b.count();
    leaf.integer = b.integer;
  } else if (std::string_view kind = std::string_view(type).starts_with("RW") ? std::string_view(type).substr(2) : type;
             kind.starts_with("Texture")) {
    // A texture member holds its texel's value in the kernel (textures_as_values), a sampler an int.
    size_t open = type.find('<');
    leaf.type = open == std::string::npos ? "float4" : type.substr(open + 1, type.rfind('>') - open - 1);
    Basic element = basic_type(leaf.type);
    if (!element.count()) return false;
    leaf.components = leaf.width = element.count();
    leaf.integer = element.integer;
  } else if (type == "SamplerState" || type == "SamplerComparisonState") {
    leaf.type = "int";
    leaf.components = leaf.width = 1;
    leaf.integer = true;
  } else if (auto s = structs.find(type); s != structs.end()) {
    bool ok = true;
    size_t first = out.size();
    for (const Field& f : s->second)
      ok &= collect_leaves(structs, f.type, path + "." + f.name, f.name, f.semantic, out, offset, depth + 1);
    for (size_t i = first; i < out.size(); ++i)
      if (out[i].owner.empty()) out[i].owner = type;
    return ok;
  } else {
    return false;
  }
  leaf.offset = offset;
  offset += leaf.width;
  out.push_back(leaf);
  return true;
}

// The component type of a vector or DoubleFloat pair (`float3` for FDFVector3), in the text's
// precision.
std::string pair_part_type(Lang lang, int n, bool float64) {
  if (lang == Lang::hlsl) return (float64 ? "double" : "float") + (n > 1 ? std::to_string(n) : "");
  if (n == 1) return float64 ? "double" : "float";
  return (float64 ? "dvec" : "vec") + std::to_string(n);
}
std::string matrix_type(Lang lang, bool float64) { return lang == Lang::hlsl ? (float64 ? "double4x4" : "float4x4") : (float64 ? "dmat4" : "mat4"); }

// The record's values `from`..`from + count - 1`, or zeros for a leaf the function never reads.
std::string ins(int from, int count, bool zero) {
  std::string s;
  for (int i = 0; i < count; ++i) s += (i ? ", " : "") + (zero ? std::string("0") : fmt::format("IN({})", from + i));
  return s;
}

// Sets an input leaf from the record, or to zero (`zero`: a member the function never reads).
void assign(const Leaf& l, Lang lang, bool float64, bool zero, std::string& body) {
  auto set = [&](const std::string& path, const std::string& type, int from, int count) {
    body += fmt::format("\t{} = {}({});\n", path, type, ins(from, count, zero));
  };
  int n = l.components;
  switch (l.encoding) {
    case Encoding::plain: set(l.path, l.type, l.offset, n); break;
    case Encoding::df: set(l.path + ".High", pair_part_type(lang, n, float64), l.offset, n);
                       set(l.path + ".Low", pair_part_type(lang, n, float64), l.offset + n, n); break;
    case Encoding::lwc: set(l.path + ".Tile", pair_part_type(lang, n, float64), l.offset, n);
                        set(l.path + ".Offset", pair_part_type(lang, n, float64), l.offset + n, n); break;
    case Encoding::df_matrix:
    case Encoding::df_inverse_matrix:
    case Encoding::lwc_matrix:
    case Encoding::lwc_inverse_matrix: {
      set(l.path + ".M", matrix_type(lang, float64), l.offset, 16);
      const char* part = l.encoding == Encoding::df_matrix ? ".PostTranslation"
                         : l.encoding == Encoding::df_inverse_matrix ? ".PreTranslation" : ".Tile";
      set(l.path + part, pair_part_type(lang, 3, float64), l.offset + 16, 3);
      break;
    }
  }
}

void write(const Leaf& l, bool float64, std::string& body) {
  const char* cast = float64 ? "double" : "float";
  auto put = [&](const std::string& expr, int at) { body += fmt::format("\tOUT({}, {}({}));\n", at, cast, expr); };
  auto vector = [&](const std::string& path, int n, int at) {
    for (int i = 0; i < n; ++i) put(n == 1 ? path : fmt::format("{}[{}]", path, i), at + i);
  };
  int n = l.components;
  switch (l.encoding) {
    case Encoding::plain: {
      Basic b = basic_type(l.type);
      if (!b.matrix) {
        vector(l.path, n, l.offset);
        break;
      }
      int k = 0;
      for (int i = 0; i < b.a; ++i)
        for (int j = 0; j < b.b; ++j) put(fmt::format("{}[{}][{}]", l.path, i, j), l.offset + k++);
      break;
    }
    case Encoding::df: vector(l.path + ".High", n, l.offset); vector(l.path + ".Low", n, l.offset + n); break;
    case Encoding::lwc: vector(l.path + ".Tile", n, l.offset); vector(l.path + ".Offset", n, l.offset + n); break;
    default: {
      int k = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) put(fmt::format("{}.M[{}][{}]", l.path, i, j), l.offset + k++);
      const char* part = l.encoding == Encoding::df_matrix ? ".PostTranslation"
                         : l.encoding == Encoding::df_inverse_matrix ? ".PreTranslation" : ".Tile";
      vector(l.path + part, 3, l.offset + 16);
    }
  }
}

// The identifier a declarator declares (looking through init/array/function declarators).
int declared_identifier(const SyntaxTree& t, int node) {
  for (int guard = 0; node >= 0 && guard < 16; ++guard) {
    if (t.is(node, "identifier") || t.is(node, "field_identifier")) return node;
    int inner = t.child_by_field(node, "declarator");
    if (inner < 0) inner = t.named_child(node);
    node = inner;
  }
  return -1;
}

// Node ids of the subtree of `id` (pre-order: contiguous).
template <typename F>
void for_subtree(const SyntaxTree& t, int id, F f) {
  uint32_t depth = t.at(id).depth;
  for (int i = id + 1; i < static_cast<int>(t.nodes.size()) && t.at(i).depth > depth; ++i) f(i);
}

struct Global {
  int node = -1;         // the declaration
  std::string name, type;
};

// A GLSL interface block (`uniform View { ... } view;`, `buffer Bounds { T bounds[]; };`): the
// kernel gets it as a private struct variable (named instance) or private globals (anonymous).
struct Block {
  std::string name, instance;   // instance "" when the members are used directly
  std::string members;          // the member declarations, as written
  bool writable = false;        // a `buffer` not declared readonly: its members are results too
};

// The `[N]` after a declared name (`uniform vec4 planes[6];`), or "".
std::string array_suffix(std::string_view declaration, std::string_view name) {
  TokenText t(declaration);
  for (size_t i = 0; i < t.size(); ++i) {
    if (!t.ident(i) || t[i] != name || t[i + 1] != "[") continue;
    if (t[i + 2] == "]") return "[]";
    std::string suffix;  // every dimension: `[2][4]`
    for (size_t k = i + 1; k + 2 < t.size() && t[k] == "[" && t.tokens[k + 1].kind != Tok::punct && t[k + 2] == "]"; k += 3)
      suffix += "[" + std::string(t[k + 1]) + "]";
    if (!suffix.empty()) return suffix;
  }
  return "";
}

// Where a call or index starts at token `i`: the index of the bracket that opens what is replaced,
// or npos.
using Head = std::function<size_t(const TokenText&, size_t)>;

// Replaces each call or index that `head` finds (from its first token through the bracket closing
// the one it opens) with what `with` makes of the text inside those brackets.
std::string replace_bracketed(std::string_view text, const Head& head, const std::function<std::string(std::string_view)>& with) {
  TokenText t(text);
  std::vector<Edit> edits;
  for (size_t i = 0; i < t.size(); ++i) {
    size_t open = head(t, i);
    if (open == std::string_view::npos) continue;
    size_t close = t.closing(open);
    if (close == std::string_view::npos) break;  // unbalanced: left to the compiler
    edits.push_back(t.replace(i, close, with(text.substr(t.tokens[open].end, t.tokens[close].begin - t.tokens[open].end))));
    i = close;
  }
  return splice(text, edits);
}

// The arguments of a call, split at top-level commas.
std::vector<std::string> split_arguments(const std::string& inside) {
  std::vector<std::string> out(1);
  int depth = 0;
  for (char c : inside) {
    if (c == '(' || c == '[') ++depth;
    if (c == ')' || c == ']') --depth;
    if (c == ',' && depth == 0) out.emplace_back();
    else out.back() += c;
  }
  return out;
}

// Textures and images become one value per invocation, `lwc_texel_NAME`: every sample, load or
// index of NAME reads it, every store or indexed write sets it (then a result). The harness checks
// arithmetic, not filtering: the value stands for whatever the texture holds at that pixel.
// (HLSL: `texel` names the value; a texture passed to a function passes it.)
void replace_texture_accesses(Lang lang, std::string& text, const std::string& name, const std::string& texel) {
  auto whole = [&](std::string_view) { return texel; };
  constexpr size_t none = std::string_view::npos;
  if (lang == Lang::hlsl) {
    text = replace_bracketed(text, [&](const TokenText& t, size_t i) {
      std::string_view method = t[i + 2];
      bool sample = method.starts_with("Sample") || method == "Load" || method.starts_with("Gather");
      return t.ident(i) && t[i] == name && t[i + 1] == "." && t.ident(i + 2) && sample && t[i + 3] == "(" ? i + 3 : none;
    }, whole);
    text = replace_bracketed(text, [&](const TokenText& t, size_t i) { return t.ident(i) && t[i] == name && t[i + 1] == "[" ? i + 1 : none; }, whole);
    // Its size: a fixed 64 texels (and 64 mip levels) to every output; with 4 or 5 arguments the
    // first is the mip level asked about, an input.
    text = replace_bracketed(text, [&](const TokenText& t, size_t i) {
      return t.ident(i) && t[i] == name && t[i + 1] == "." && t[i + 2] == "GetDimensions" && t[i + 3] == "(" ? i + 3 : none;
    }, [](std::string_view inside) {
      std::vector<std::string> args = split_arguments(std::string(inside));
      std::string out;
      for (size_t a = args.size() >= 4 ? 1 : 0; a < args.size(); ++a) out += (out.empty() ? "" : ", ") + args[a] + " = 64";
      return "(" + out + ")";
    });
    if (texel == name) return;
    TokenText t(text);
    std::vector<Edit> bare;
    for (size_t i = 0; i < t.size(); ++i)
      if (t.ident(i) && t[i] == name && (i == 0 || t[i - 1] != ".")) bare.push_back(t.replace(i, i, texel));
    text = splice(text, bare);
    return;
  }
  auto image_call = [&](const TokenText& t, size_t i) { return t[i + 1] == "(" && t.ident(i + 2) && t[i + 2] == name && t[i + 3] == ","; };
  text = replace_bracketed(text, [&](const TokenText& t, size_t i) { return t.ident(i) && t[i] == "imageStore" && image_call(t, i) ? i + 1 : none; },
                           [&](std::string_view inside) { return "(" + texel + " = " + split_arguments(std::string(inside)).back() + ")"; });
  text = replace_bracketed(text, [&](const TokenText& t, size_t i) {
    std::string_view f = t[i];
    bool read = f.starts_with("texture") || f.starts_with("texelFetch") || f == "imageLoad";
    return t.ident(i) && read && image_call(t, i) ? i + 1 : none;
  }, whole);
}

// HLSL texture and sampler declarations between the tokens `open` and `close` (a parameter list,
// a struct body): a texture becomes the value of its texel, a sampler an unused int; `textures`
// gets the textures' names.
std::string textures_as_values(const std::string& text, bool float64, size_t open, size_t close, std::vector<std::string>& textures) {
  TokenText t(text);
  std::vector<Edit> edits;
  for (size_t i = open + 1; i < close; ++i) {
    std::string_view kind = t[i].starts_with("RW") ? t[i].substr(2) : t[i];
    if (!t.ident(i) || (t[i - 1] != "," && t[i - 1] != "(" && t[i - 1] != "in" && t[i - 1] != ";" && t[i - 1] != "{")) continue;
    if (kind == "SamplerState" || kind == "SamplerComparisonState") {
      edits.push_back(t.replace(i, i, "int"));
    } else if (kind.starts_with("Texture")) {
      std::string element = float64 ? "double4" : "float4";
      size_t name_at = i + 1;
      if (t[i + 1] == "<") {
        element.clear();
        for (name_at = i + 2; name_at < close && t[name_at] != ">"; ++name_at) element += t[name_at];
        ++name_at;
      }
      if (name_at < close && t.ident(name_at) && (t[name_at + 1] == "," || t[name_at + 1] == ")" || t[name_at + 1] == ";")) {
        edits.push_back(t.replace(i, name_at - 1, element));
        textures.emplace_back(t[name_at]);
      }
    }
  }
  return splice(text, edits);
}

// A function's texture and sampler parameters as values: its samples of a texture read the value
// (the caller passes the value of its own); a struct's members are done the same way, and
// `Resources.Irradiance.SampleLevel(..)` reads the member.
std::string texture_parameters_as_values(const std::string& function_text, bool float64) {
  TokenText t(function_text);
  size_t open = 0;
  while (open < t.size() && t[open] != "(") ++open;
  size_t close = open < t.size() ? t.closing(open) : std::string_view::npos;
  if (close == std::string_view::npos) return function_text;
  std::vector<std::string> textures;
  std::string out = textures_as_values(function_text, float64, open, close, textures);
  for (const std::string& name : textures) replace_texture_accesses(Lang::hlsl, out, name, name);
  return out;
}

// The double twin of a float type (`float3` -> `double3`, `vec3` -> `dvec3`, `mat4x3` ->
// `dmat4x3`), or "" for any other word.
std::string double_type(Lang lang, std::string_view word) {
  if (lang == Lang::hlsl) {
    for (std::string_view scalar : {"float", "half", "min16float"})
      if (word.starts_with(scalar) && (word.size() == scalar.size() || basic_type("float" + std::string(word.substr(scalar.size()))).count()))
        return "double" + std::string(word.substr(scalar.size()));
    return "";
  }
  if (word == "float") return "double";
  Basic b = basic_type(word);
  return b.count() > 1 && !b.integer && (word.starts_with("vec") || word.starts_with("mat")) ? "d" + std::string(word) : "";
}

// The text without its `#version` line (the kernel has its own).
std::string without_version(std::string_view text) {
  TokenText t(text);
  std::vector<Edit> edits;
  for (size_t i = 0; i < t.size(); ++i)
    if (t.tokens[i].kind == Tok::directive && read_directive(t[i]).keyword == "version") edits.push_back(t.replace(i, i, ""));
  return splice(text, edits);
}

// An entry point written through an engine macro, `RAY_TRACING_ENTRY_RAYGEN(Name) { .. }`: the
// function is `Name` once the macro is expanded. (tree-sitter-hlsl may split the macro's name
// into a type and a declarator, `RAY_` + `TRACING_ENTRY_RAYGEN`: both halves are read.)
std::optional<std::string> entry_macro_function(const SyntaxTree& t, int definition, int id) {
  uint32_t begin = t.at(id).begin;
  if (int type = t.child_by_field(definition, "type"); type >= 0 && t.at(type).end == begin) begin = t.at(type).begin;
  std::string_view macro = std::string_view(t.source->text()).substr(begin, t.at(id).end - begin);
  bool upper = macro.size() > 2;
  for (char ch : macro) upper &= (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
  int declarator = t.child_by_field(definition, "declarator");
  int params = declarator >= 0 ? t.child_by_field(declarator, "parameters") : -1;
  if (!upper || params < 0) return std::nullopt;
  TokenText inside(t.text(params));
  if (inside.size() == 3 && inside.ident(1)) return std::string(inside[1]);
  return std::nullopt;
}

}  // namespace

std::vector<std::string> enclosing_functions(Lang lang, const std::string& text, const std::vector<uint32_t>& offsets) {
  if (offsets.empty()) return {};  // no parse: most files of a tree have no finding
  Source source("file", text);
  SyntaxTree t = parse(source, lang);
  std::vector<std::string> out;
  for (uint32_t at : offsets) {
    std::string name;
    // Down through whatever holds the offset (include guards, #if blocks) to a function.
    for (int c = t.at(0).first_child; c >= 0 && name.empty();) {
      if (!(t.at(c).begin <= at && at < t.at(c).end)) {
        c = t.at(c).next_sibling;
        continue;
      }
      if (t.is(c, "function_definition")) {
        int id = declared_identifier(t, t.child_by_field(c, "declarator"));
        if (id >= 0) name = entry_macro_function(t, c, id).value_or(std::string(t.text(id)));
      }
      c = t.at(c).first_child;
    }
    out.push_back(name);
  }
  return out;
}

// A float's bits read as an integer (a packed datum, not a value): in the reference they are the
// bits of the float32 value, read through a wrapper the narrowing check knows.
const std::set<std::string_view>& bit_casts(Lang lang) {
  static const std::set<std::string_view> hlsl = {"asuint", "asint"}, glsl = {"floatBitsToUint", "floatBitsToInt"};
  return lang == Lang::hlsl ? hlsl : glsl;
}

std::string promote_to_double(Lang lang, const std::string& text) {
  // Transcendentals have no double form on the GPU: they run in float32 (on small values, as a rule).
  static const std::set<std::string_view> float32_only = {"sin",  "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh",
                                                           "tanh", "pow", "exp", "log",  "exp2", "log2", "log10"};
  TokenText t(text);
  std::vector<Edit> edits;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!t.ident(i)) continue;
    // No precision statements for double.
    if (t[i] == "precision" && t.ident(i + 1) && (t[i + 2] == "double" || double_type(lang, t[i + 2]) == "double") && t[i + 3] == ";") {
      edits.push_back(t.replace(i, i + 3, ""));
      i += 3;
    } else if (std::string twin = double_type(lang, t[i]); !twin.empty()) {
      edits.push_back(t.replace(i, i, twin));
    } else if ((float32_only.count(t[i]) || bit_casts(lang).count(t[i])) && t[i + 1] == "(") {
      edits.push_back(t.replace(i, i, "lwc_f32_" + std::string(t[i])));
    } else if (lang == Lang::hlsl && narrowed_hlsl_intrinsics().count(t[i]) && t[i + 1] == "(") {
      edits.push_back(t.replace(i, i, "lwc_d_" + std::string(t[i])));
    }
  }
  return splice(text, edits);
}

HarnessKernel build_harness_kernel(Lang lang, const std::string& input_text, const std::string& function, bool float64) {
  HarnessKernel k;
  std::string text = without_version(input_text);
  Source source("kernel", text);
  SyntaxTree t = parse(source, lang);
  std::string masked = lang == Lang::hlsl ? mask_source(text, lang).text : text;
  auto slice = [&](const std::string& s, int id) { return s.substr(t.at(id).begin, t.at(id).end - t.at(id).begin); };
  Structs structs = read_structs(text);

  // Top-level items: functions by name, globals (cbuffer members included).
  std::map<std::string, std::vector<int>> functions;
  std::vector<Global> globals;
  std::vector<int> top;
  for (int c = t.at(0).first_child; c >= 0; c = t.at(c).next_sibling) top.push_back(c);
  std::map<int, Block> blocks;  // declaration node -> block
  auto add_block = [&](int decl) {
    Block b;
    int list = -1;
    bool buffer = false, readonly = false;
    for (int d = t.at(decl).first_child; d >= 0; d = t.at(d).next_sibling) {
      if (t.is(d, "field_declaration_list")) list = d;
      else if (t.is(d, "identifier")) (list < 0 ? b.name : b.instance) = std::string(t.text(d));
      buffer |= t.is(d, "buffer");
      readonly |= t.is(d, "readonly");
    }
    std::string body = slice(text, list);
    b.members = body.substr(1, body.size() - 2);
    b.writable = buffer && !readonly;
    std::string block_struct = "lwc_block_" + b.name;
    for (const auto& [struct_name, fields] : read_structs("struct " + block_struct + " {" + b.members + "}")) {
      structs[struct_name] = fields;
      if (b.instance.empty())
        for (const Field& f : fields) globals.push_back({decl, f.name, f.type});
      else
        globals.push_back({decl, b.instance, block_struct});
    }
    blocks[decl] = b;
  };
  auto add_globals = [&](int decl) {
    int type = t.child_by_field(decl, "type");
    for (int d = t.at(decl).first_child; d >= 0; d = t.at(d).next_sibling) {
      if (!t.at(d).field || std::string_view(t.at(d).field) != "declarator") continue;
      if (t.is(d, "function_declarator")) return;
      int id = declared_identifier(t, d);
      if (id >= 0) globals.push_back({decl, std::string(t.text(id)), type >= 0 ? slice(masked, type) : ""});
    }
  };
  for (int c : top) {
    if (t.is(c, "function_definition")) {
      int id = declared_identifier(t, t.child_by_field(c, "declarator"));
      if (id >= 0) functions[std::string(t.text(id))].push_back(c);
    } else if (t.is(c, "declaration")) {
      bool block = false;
      for (int d = t.at(c).first_child; d >= 0; d = t.at(d).next_sibling) block |= t.is(d, "field_declaration_list");
      if (block && lang == Lang::glsl) add_block(c);
      else add_globals(c);
    } else if (t.is(c, "linkage_specification")) {
      for_subtree(t, c, [&](int i) { if (t.is(i, "declaration")) add_globals(i); });
    }
  }
  if (!functions.count(function)) {
    k.problem = fmt::format("no definition of `{}` after preprocessing", function);
    return k;
  }

  // What the function needs: the functions it calls (all overloads), the globals it reads.
  std::set<std::string> needed = {function}, used;
  std::vector<std::string> work = {function};
  std::set<std::string> global_names;
  for (const Global& g : globals) global_names.insert(g.name);
  while (!work.empty()) {
    std::string f = work.back();
    work.pop_back();
    for (int def : functions[f])
      for_subtree(t, def, [&](int i) {
        if (!t.is(i, "identifier")) return;
        std::string name(t.text(i));
        if (functions.count(name) && needed.insert(name).second) work.push_back(name);
        if (global_names.count(name)) used.insert(name);
      });
  }
  // The member names the needed code reads (`View.WorldCameraOrigin`, `p.Position`): an input
  // leaf reached through another member is never read, so it is set to zero in the kernel rather
  // than drawn for every invocation (Unreal's View struct has hundreds of members; a function
  // reads a few).
  std::set<std::string, std::less<>> members_read;
  for (const std::string& f : needed)
    for (int def : functions[f])
      for_subtree(t, def, [&](int i) {
        if (t.is(i, "field_identifier")) members_read.emplace(t.text(i));
      });
  auto reads = [&](const Leaf& leaf) {
    std::string_view path = leaf.path;
    for (size_t dot = path.find('.'); dot != std::string_view::npos; dot = path.find('.', dot + 1)) {
      size_t end = path.find_first_of(".[", dot + 1);
      if (!members_read.count(path.substr(dot + 1, end == std::string_view::npos ? end : end - dot - 1))) return false;
    }
    return true;
  };
  bool glsl_main = lang == Lang::glsl && function == "main";

  // The struct types the needed code names, and the types their members name in turn: others are
  // left out, so a header's structs the function never sees (an engine's, a platform's) cannot
  // keep its kernel from compiling.
  std::map<std::string, int> struct_nodes;
  for (int c : top)
    if (t.is(c, "struct_specifier"))
      if (int name = t.child_by_field(c, "name"); name >= 0) struct_nodes.emplace(std::string(t.text(name)), c);
  std::set<std::string> types_named;
  std::vector<int> to_scan;
  for (const std::string& f : needed)
    for (int def : functions[f]) to_scan.push_back(def);
  for (const Global& g : globals)
    if (used.count(g.name)) to_scan.push_back(g.node);
  while (!to_scan.empty()) {
    int node = to_scan.back();
    to_scan.pop_back();
    for_subtree(t, node, [&](int i) {
      if (!t.is(i, "type_identifier") && !t.is(i, "identifier")) return;
      auto s = struct_nodes.find(std::string(t.text(i)));
      if (s != struct_nodes.end() && types_named.insert(s->first).second) to_scan.push_back(s->second);
    });
  }

  // The declarations: kept functions and types as written, environment globals made private.
  std::string decl;
  std::vector<std::string> textures;  // globals whose accesses become `lwc_texel_NAME`
  // `x[]` block members: the tokens that name one (`x`, or `block . x`), and the element read.
  std::vector<std::pair<std::vector<std::string>, std::string>> runtime_arrays;
  std::vector<std::pair<std::string, std::string>> env_inputs, env_outputs;  // name, type
  auto global_text = [&](const Global& g) -> std::string {
    std::string original = slice(text, g.node);
    TokenText d(original);
    if (lang == Lang::hlsl) {
      std::string_view kind = d[0];
      bool writable = kind.starts_with("RW");
      std::string_view resource = writable ? kind.substr(2) : kind;
      if ((resource == "Buffer" || resource == "StructuredBuffer") && d.spells(1, {"<", "", ">", ""})) {
        std::string element(d[2]), name(d[4]);
        env_inputs.push_back({name + "[0]", element});
        if (writable) env_outputs.push_back({name + "[0]", element});
        return fmt::format("static {} {}[1];", element, name);
      }
      bool typed = d.spells(1, {"<", "", ">"});
      if (resource.starts_with("Texture") && d.ident(typed ? 4 : 1)) {
        std::string type = typed ? std::string(d[2]) : float64 ? "double4" : "float4";
        textures.push_back(g.name);
        env_inputs.push_back({"lwc_texel_" + g.name, type});
        if (writable) env_outputs.push_back({"lwc_texel_" + g.name, type});
        return fmt::format("static {} lwc_texel_{};", type, g.name);
      }
      // A sampler is an argument of the samples replaced, or of a function whose sampler parameter
      // becomes an unused int (texture_parameters_as_values).
      if (kind == "SamplerState" || kind == "SamplerComparisonState") return "static const int " + g.name + " = 0;";
      if (kind.starts_with("sampler")) return "";
      for (std::string_view other : {"Texture", "Sampler", "sampler", "texture", "image", "ByteAddressBuffer", "AppendStructuredBuffer", "ConsumeStructuredBuffer"})
        if (resource.starts_with(other)) {
          k.problem = fmt::format("`{}` is a texture or sampler: not filled by the harness", g.name);
          return "";
        }
      std::string masked_decl = slice(masked, g.node);
      TokenText m(masked_decl);
      if (m[0] == "static" || m[0] == "const") return masked_decl;
      // Workgroup scratch memory (the masked `groupshared` sits before the node): the group's,
      // written before it is read, not an input.
      size_t line = text.rfind('\n', t.at(g.node).begin);
      line = line == std::string::npos ? 0 : line + 1;
      TokenText before(std::string_view(text).substr(line, t.at(g.node).begin - line));
      for (size_t w = 0; w < before.size(); ++w)
        if (before[w] == "groupshared") return masked_decl;
      env_inputs.push_back({g.name, g.type + array_suffix(original, g.name)});
      return "static " + masked_decl;
    }
    if (auto block = blocks.find(g.node); block != blocks.end()) {
      const Block& b = block->second;
      // Runtime-sized arrays hold one element: every index of them reads element 0.
      TokenText m(b.members);
      std::vector<Edit> sized;
      for (size_t i = 0; i + 1 < m.size(); ++i)
        if (m[i] == "[" && m[i + 1] == "]") sized.push_back(m.replace(i, i + 1, "[1]"));
      std::string members = splice(b.members, sized);
      if (b.instance.empty()) {
        for (const Global& member : globals)
          if (member.node == g.node) {
            env_inputs.push_back({member.name, member.type});
            if (b.writable) env_outputs.push_back({member.name, member.type});
            if (member.type.ends_with("[]")) runtime_arrays.push_back({{member.name}, member.name + "[0]"});
          }
        return members;
      }
      env_inputs.push_back({b.instance, g.type});
      if (b.writable) env_outputs.push_back({b.instance, g.type});
      for (const Field& f : structs[g.type])
        if (f.type.ends_with("[]")) runtime_arrays.push_back({{b.instance, ".", f.name}, b.instance + "." + f.name + "[0]"});
      return fmt::format("struct {} {{{}}};\n{} {};", g.type, members, g.type, b.instance);
    }
    for (size_t i = 0; i < d.size(); ++i) {
      // `uniform sampler2D name;`, `uniform isampler3D name;`, `writeonly image2D name;`
      std::string_view word = d[i], kind = word.substr(0, 1);
      if (kind == "i" || kind == "u") word.remove_prefix(1);
      if (!word.starts_with("sampler") && !word.starts_with("image")) word = d[i], kind = "";
      if (!d.ident(i) || !(word.starts_with("sampler") || word.starts_with("image")) || !d.spells(i + 1, {"", ";"})) continue;
      std::string type = kind == "i" ? "ivec4" : kind == "u" ? "uvec4" : float64 ? "dvec4" : "vec4";
      textures.push_back(g.name);
      env_inputs.push_back({"lwc_texel_" + g.name, type});
      if (word.starts_with("image")) env_outputs.push_back({"lwc_texel_" + g.name, type});
      return fmt::format("{} lwc_texel_{};", type, g.name);
    }
    if (d[0] == "const") return original;
    static const std::set<std::string_view> qualifiers = {"uniform", "in", "out", "inout", "varying", "attribute", "flat", "smooth",
                                                          "noperspective", "centroid", "invariant", "readonly", "writeonly",
                                                          "coherent", "volatile", "restrict"};
    bool output = false;
    std::vector<Edit> unqualified;
    for (size_t i = 0; i < d.size(); ++i) {
      if (!d.ident(i)) continue;
      output |= d[i] == "out" || d[i] == "varying";
      size_t last = i;
      if (d.spells(i, {"layout", "("})) last = d.closing(i + 1);
      else if (!qualifiers.count(d[i])) continue;
      if (last == std::string_view::npos) break;
      unqualified.push_back(d.replace(i, last, ""));
      i = last;
    }
    (output ? env_outputs : env_inputs).push_back({g.name, g.type + array_suffix(original, g.name)});
    return splice(original, unqualified);
  };
  // Real lines for a float32 HLSL kernel; a float64 one keeps its own (the SPIR-V's OpLines name
  // the lines of the kernel's text, where it narrows to float32).
  LineMap lines(lang == Lang::hlsl && !float64 ? std::string_view(text) : std::string_view());
  bool dropped_struct = false;  // the item before: its `;` goes with it
  std::vector<std::string> texture_members;  // of kept structs: each reads its value
  for (size_t i = 0; i < top.size(); ++i) {
    int c = top[i];
    uint32_t gap_begin = i ? t.at(top[i - 1]).end : 0;
    if (dropped_struct)
      if (size_t semicolon = text.find(';', gap_begin); semicolon < t.at(c).begin) gap_begin = static_cast<uint32_t>(semicolon + 1);
    dropped_struct = false;
    std::string gap = text.substr(gap_begin, t.at(c).begin - gap_begin);
    if (lang == Lang::hlsl) gap = without_line_directives(gap);
    std::string item;
    bool keep = true;
    if (t.is(c, "function_definition")) {
      int id = declared_identifier(t, t.child_by_field(c, "declarator"));
      std::string name = id >= 0 ? std::string(t.text(id)) : "";
      keep = needed.count(name) > 0;
      item = slice(text, c);
      if (keep && glsl_main && name == "main")
        item.replace(t.at(id).begin - t.at(c).begin, 4, "lwc_entry");
      if (keep && lang == Lang::hlsl) item = texture_parameters_as_values(item, float64);
      // Blocks come before the functions that use them: their runtime-sized arrays are known.
      for (const auto& array : runtime_arrays) {
        auto head = [&](const TokenText& t, size_t i) {
          for (const std::string& w : array.first)
            if (t[i++] != w) return std::string_view::npos;
          return t[i] == "[" ? i : std::string_view::npos;
        };
        item = replace_bracketed(item, head, [&](std::string_view) { return array.second; });
      }
    } else if (t.is(c, "declaration") || t.is(c, "linkage_specification")) {
      std::vector<const Global*> mine;
      for (const Global& g : globals)
        if (g.node == c || (t.is(c, "linkage_specification") && t.at(g.node).begin >= t.at(c).begin && t.at(g.node).end <= t.at(c).end))
          mine.push_back(&g);
      if (mine.empty()) {
        item = slice(text, c);  // a struct definition, a prototype
      } else {
        std::set<int> done;
        for (const Global* g : mine) {
          if (!used.count(g->name) || done.count(g->node)) continue;
          done.insert(g->node);
          item += global_text(*g) + "\n";
        }
        keep = !item.empty();
      }
    } else if (t.is(c, "struct_specifier") && t.child_by_field(c, "name") >= 0) {
      item = slice(text, c);
      keep = types_named.count(std::string(t.text(t.child_by_field(c, "name")))) > 0;
      dropped_struct = !keep;
    } else {
      item = slice(text, c);
      keep = !(lang == Lang::hlsl && is_line_directive(item));  // the kernel writes its own, below
    }
    if (keep && lang == Lang::hlsl && item.starts_with("struct")) {
      TokenText body(item);
      size_t open = 0, close = body.size();
      while (open < body.size() && body[open] != "{") ++open;
      while (close > open && body[close - 1] != "}") --close;
      if (close > open + 1) item = textures_as_values(item, float64, open, close - 1, texture_members);
    }
    // Other text before an item (an HLSL attribute such as [numthreads(..)]) goes with it.
    if (keep && !lines.empty()) {
      size_t start = t.at(c).begin;  // or the first text of the gap that is not a `#line`
      std::string_view raw = std::string_view(text).substr(gap_begin, t.at(c).begin - gap_begin);
      for (size_t line = 0; line < raw.size();) {
        size_t end = std::min(raw.find('\n', line), raw.size());
        std::string_view l = raw.substr(line, end - line);
        if (size_t first = l.find_first_not_of(" \t\r"); first != std::string_view::npos && !is_line_directive(l)) {
          start = gap_begin + line + first;
          break;
        }
        line = end + 1;
      }
      decl += "\n" + lines.directive(start) + without_line_directives(text.substr(start, t.at(c).begin - start)) + item;
      continue;
    }
    if (keep || blank(gap)) decl += gap;
    if (keep) decl += item;
  }
  if (!lines.empty()) decl += "\n#line 1 \"lwcport kernel\"\n";  // the harness's own code after it
  k.real_lines = !lines.empty();
  if (!k.problem.empty()) return k;
  for (const std::string& name : textures) replace_texture_accesses(lang, decl, name, "lwc_texel_" + name);
  for (const std::string& name : texture_members) replace_texture_accesses(lang, decl, name, name);


  // GLSL stage built-ins become private globals.
  static const std::map<std::string, std::pair<std::string, bool>, std::less<>> builtins = {
      {"gl_Position", {"vec4", true}}, {"gl_PointSize", {"float", true}}, {"gl_FragCoord", {"vec4", false}},
      {"gl_VertexID", {"int", false}}, {"gl_InstanceID", {"int", false}}, {"gl_FrontFacing", {"bool", false}}};
  std::string prefix;
  if (lang == Lang::glsl) {
    std::set<std::string, std::less<>> seen;
    decl = rename_identifiers(decl, [&](std::string_view word) {
      if (!builtins.count(word)) return std::string();
      seen.emplace(word);
      return "lwc_" + std::string(word);
    });
    for (const auto& [name, info] : builtins) {
      if (!seen.count(name)) continue;
      std::string type = float64 ? promote_to_double(lang, info.first) : info.first;
      prefix += type + " lwc_" + name + ";\n";
      (info.second ? env_outputs : env_inputs).push_back({"lwc_" + name, type});
    }
  }
  if (float64) {
    // float32 transcendentals for the double reference (see promote_to_double).
    std::string d = "double", f = "float";
    std::string v = lang == Lang::hlsl ? "double" : "dvec", fv = lang == Lang::hlsl ? "float" : "vec";
    std::vector<const char*> unary = {"sin", "cos", "tan", "asin", "acos", "atan", "sinh", "cosh", "tanh", "exp", "log", "exp2", "log2"};
    if (lang == Lang::hlsl) unary.push_back("log10");
    for (const char* fn : unary) {
      prefix += fmt::format("{0} lwc_f32_{1}({0} x) {{ return {0}({1}({2}(x))); }}\n", d, fn, f);
      for (int n = 2; n <= 4; ++n) prefix += fmt::format("{0}{3} lwc_f32_{1}({0}{3} x) {{ return {0}{3}({1}({2}{3}(x))); }}\n", v, fn, fv, n);
    }
    // Two arguments: pow, and the angle of (y, x): HLSL's atan2, GLSL's atan.
    for (const char* fn : {"pow", lang == Lang::hlsl ? "atan2" : "atan"}) {
      prefix += fmt::format("{0} lwc_f32_{2}({0} x, {0} y) {{ return {0}({2}({1}(x), {1}(y))); }}\n", d, f, fn);
      for (int n = 2; n <= 4; ++n)
        prefix += fmt::format("{0}{2} lwc_f32_{3}({0}{2} x, {0}{2} y) {{ return {0}{2}({3}({1}{2}(x), {1}{2}(y))); }}\n", v, fv, n, fn);
    }
    // Bit casts (see bit_casts): of a double, the float32 value's bits; of an HLSL integer, as written.
    auto type = [&](std::string_view scalar, int n) -> std::string {
      if (n == 1) return std::string(scalar);
      if (lang == Lang::hlsl) return fmt::format("{}{}", scalar, n);
      return fmt::format("{}vec{}", scalar == "double" ? "d" : scalar == "uint" ? "u" : scalar == "int" ? "i" : "", n);
    };
    for (std::string_view cast : bit_casts(lang)) {
      std::string_view result = cast.ends_with("uint") || cast.ends_with("Uint") ? "uint" : "int";
      for (int n = 1; n <= 4; ++n) {
        prefix += fmt::format("{0} lwc_f32_{1}({2} x) {{ return {1}({3}(x)); }}\n", type(result, n), cast, type("double", n), type("float", n));
        if (lang == Lang::hlsl)
          for (std::string_view integer : {"int", "uint"})
            prefix += fmt::format("{0} lwc_f32_{1}({2} x) {{ return {1}(x); }}\n", type(result, n), cast, type(integer, n));
      }
    }
    if (lang == Lang::hlsl) prefix += hlsl_double_intrinsics();
  }
  k.declarations = prefix + decl;

  // The entry body: parameters as locals, then every input filled, the call, every output written.
  int def = functions[function].front();
  int declarator = t.child_by_field(def, "declarator");
  int params = -1;
  for (int d = declarator; d >= 0 && params < 0; d = t.child_by_field(d, "declarator"))
    params = t.child_by_field(d, "parameters");
  std::string return_type;
  if (int rt = t.child_by_field(def, "type"); rt >= 0) return_type = slice(masked, rt);
  std::vector<std::string> args;
  std::string body;
  int in_offset = 0, out_offset = 0;
  std::string fill;
  auto add_inputs = [&](const std::string& type, const std::string& path, const std::string& name, const std::string& semantic = "") {
    std::vector<Leaf> leaves;
    int width = 0;
    if (!collect_leaves(structs, type, path, name, semantic, leaves, width))
      k.problem = fmt::format("`{}` has type `{}`, which the harness cannot fill", name, type);
    for (Leaf& leaf : leaves) {
      if (!reads(leaf)) {
        assign(leaf, lang, float64, true, fill);
        continue;
      }
      leaf.offset = in_offset;
      in_offset += leaf.width;
      k.inputs.push_back(std::move(leaf));
    }
  };
  auto add_outputs = [&](const std::string& type, const std::string& path, const std::string& name, const std::string& semantic = "") {
    if (!collect_leaves(structs, type, path, name, semantic, k.outputs, out_offset))
      k.problem = fmt::format("`{}` has type `{}`, which the harness cannot read", name, type);
  };
  if (params >= 0) {
    int index = 0;
    for (int p : t.named_children(params)) {
      if (!t.is(p, "parameter_declaration")) continue;
      int type = t.child_by_field(p, "type");
      int id = declared_identifier(t, t.child_by_field(p, "declarator"));
      if (type < 0 || id < 0) continue;
      std::string ptype = slice(masked, type), pname(t.text(id));
      // From the previous `(` or `,`: HLSL's masking hides `in`/`out` from the parser, so they sit
      // before the parameter's node.
      size_t from = text.find_last_of("(,", t.at(p).begin - 1) + 1;
      std::string original = text.substr(from, t.at(p).end - from);
      std::string_view direction = TokenText(original)[0];
      bool out = direction == "out" || direction == "inout";
      bool in = direction != "out";
      std::string local = fmt::format("lwc_p{}", index++);
      // Its HLSL semantic (`out float4 Color : SV_Target0`): a render target's value is unitless.
      // (The parser's node ends before it: semantics are masked.)
      std::string semantic;
      size_t end = text.find_first_of(",)", t.at(p).end);
      TokenText after(std::string_view(text).substr(t.at(p).end, end == std::string::npos ? 0 : end - t.at(p).end));
      if (after.size() == 2 && after[0] == ":" && after.ident(1)) semantic = after[1];
      std::string dimensions = array_suffix(original, pname);  // `inout T x[2][4]`
      body += fmt::format("\t{} {}{};\n", ptype, local, dimensions);
      ptype += dimensions;
      if (in) add_inputs(ptype, local, pname, semantic);
      if (out) add_outputs(ptype, local, pname, semantic);
      args.push_back(local);
    }
  }
  for (const auto& [name, type] : env_inputs) add_inputs(type, name, name);
  for (const auto& [name, type] : env_outputs) add_outputs(type, name, name);
  std::string call = fmt::format("{}({})", glsl_main ? "lwc_entry" : function, fmt::join(args, ", "));
  std::string call_statement = "\t" + call + ";\n";
  if (!return_type.empty() && return_type != "void") {
    call_statement = fmt::format("\t{} lwc_result = {};\n", return_type, call);
    add_outputs(return_type, "lwc_result", "return");
  }
  for (const Leaf& l : k.inputs) assign(l, lang, float64, false, fill);
  std::string read;
  for (const Leaf& l : k.outputs) write(l, float64, read);
  k.body = body + fill + call_statement + read;
  k.in_stride = std::max(in_offset, 1);
  k.out_stride = std::max(out_offset, 1);
  if (k.outputs.empty() && k.problem.empty()) k.problem = fmt::format("`{}` has no result to compare (no return value, out parameter or stage output)", function);
  return k;
}

// Its line kept, so offsets within lines shift only.
std::string without_line_directives(std::string text) {
  for (size_t begin = 0; begin < text.size();) {
    size_t end = std::min(text.find('\n', begin), text.size());
    if (is_line_directive(std::string_view(text).substr(begin, end - begin))) text.erase(begin, end - begin), end = begin;
    begin = end + 1;
  }
  return text;
}

}  // namespace lwc
