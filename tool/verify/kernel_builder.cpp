#include "verify/kernel_builder.h"

#include <fmt/format.h>

#include <functional>
#include <map>
#include <regex>
#include <set>

#include "lang/mask.h"

namespace lwc {

namespace {

struct Field {
  std::string type, name, semantic;
};
using Structs = std::map<std::string, std::vector<Field>>;

// Text between top-level items that belongs to no item of its own: white space, and the `;`
// that ends a struct definition (the grammar leaves it outside the struct's node).
bool blank(std::string_view s) { return s.find_first_not_of(" \t\r\n;") == std::string_view::npos; }

// Struct definitions of a preprocessed text (macros already expanded).
Structs read_structs(const std::string& text) {
  Structs out;
  static const std::regex def(R"(\bstruct\s+(\w+)\s*\{([^}]*)\})");
  static const std::regex qualifier(R"(\b(precise|nointerpolation|linear|centroid|noperspective|sample|flat|smooth|highp|mediump|lowp)\b)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), def); it != std::sregex_iterator(); ++it) {
    std::vector<Field>& fields = out[(*it)[1]];
    std::string body = (*it)[2];
    size_t start = 0;
    for (size_t semi; (semi = body.find(';', start)) != std::string::npos; start = semi + 1) {
      std::string piece = std::regex_replace(body.substr(start, semi - start), qualifier, " ");
      static const std::regex field(R"(^\s*(\w+)\s+(.+?)\s*$)");
      std::smatch m;
      if (!std::regex_match(piece, m, field)) continue;
      std::string type = m[1], names = m[2];
      size_t from = 0;
      for (size_t comma; from <= names.size(); from = comma + 1) {
        comma = names.find(',', from);
        if (comma == std::string::npos) comma = names.size();
        static const std::regex declarator(R"(^\s*(\w+)\s*(\[[^\]]*\])?\s*(?::\s*(\w+))?\s*$)");
        std::smatch d;
        std::string one = names.substr(from, comma - from);
        if (std::regex_match(one, d, declarator)) fields.push_back({d[2].matched ? type + d[2].str() : type, d[1], d[3]});
      }
    }
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
Basic basic_type(const std::string& type) {
  static const std::regex hlsl(R"(^(float|half|double|min16float|int|uint|bool|dword)([1-4])?(?:x([1-4]))?$)");
  static const std::regex glsl_vec(R"(^([dbiu]?)vec([2-4])$)");
  static const std::regex glsl_mat(R"(^d?mat([2-4])(?:x([2-4]))?$)");
  std::smatch m;
  if (std::regex_match(type, m, hlsl)) {
    Basic b;
    b.integer = m[1] == "int" || m[1] == "uint" || m[1] == "bool" || m[1] == "dword";
    b.a = m[2].matched ? std::stoi(m[2]) : 1;
    b.b = m[3].matched ? std::stoi(m[3]) : 1;
    b.matrix = m[3].matched;
    return b;
  }
  if (std::regex_match(type, m, glsl_vec)) return {std::stoi(m[2]), 1, false, m[1] == "b" || m[1] == "i" || m[1] == "u"};
  if (std::regex_match(type, m, glsl_mat)) {
    int c = std::stoi(m[1]);
    return {c, m[2].matched ? std::stoi(m[2]) : c, true, false};
  }
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
    if (n < 1 || n > 64 || type.find('[', bracket + 1) != std::string::npos) return false;
    for (int i = 0; i < n; ++i)
      if (!collect_leaves(structs, type.substr(0, bracket), fmt::format("{}[{}]", path, i), name, semantic, out, offset, depth + 1))
        return false;
    return true;
  }
  Leaf leaf{path, name, type, semantic};
  if (auto special = special_encoding(type)) {
    leaf.encoding = special->first;
    leaf.components = special->second;
    leaf.width = leaf.encoding == Encoding::df || leaf.encoding == Encoding::lwc ? 2 * leaf.components : 16 + 3;
  } else if (Basic b = basic_type(type); b.count()) {
    leaf.components = leaf.width = b.count();
    leaf.integer = b.integer;
  } else if (auto s = structs.find(type); s != structs.end()) {
    bool ok = true;
    for (const Field& f : s->second)
      ok &= collect_leaves(structs, f.type, path + "." + f.name, f.name, f.semantic, out, offset, depth + 1);
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

std::string ins(int from, int count) {
  std::string s;
  for (int i = 0; i < count; ++i) s += (i ? ", " : "") + fmt::format("IN({})", from + i);
  return s;
}

void assign(const Leaf& l, Lang lang, bool float64, std::string& body) {
  auto set = [&](const std::string& path, const std::string& type, int from, int count) {
    body += fmt::format("\t{} = {}({});\n", path, type, ins(from, count));
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

// glslang's HLSL has `mul` and `transpose` for float matrices only: the double reference gets
// its own, row by row as HLSL defines them (row vectors on the left, rows of the matrix).
std::string hlsl_double_matrix_functions() {
  std::string out;
  for (int n = 2; n <= 4; ++n)
    for (int m = 2; m <= 4; ++m) {
      out += fmt::format("double{1} mul(double{0} v, double{0}x{1} a) {{ double{1} r = 0; for (int i = 0; i < {0}; ++i) r += v[i] * a[i]; return r; }}\n", n, m);
      out += fmt::format("double{0} mul(double{0}x{1} a, double{1} v) {{ double{0} r; for (int i = 0; i < {0}; ++i) {{ double s = 0; "
                         "for (int j = 0; j < {1}; ++j) s += a[i][j] * v[j]; r[i] = s; }} return r; }}\n", n, m);
      out += fmt::format("double{1}x{0} transpose(double{0}x{1} a) {{ double{1}x{0} r; for (int i = 0; i < {0}; ++i) "
                         "for (int j = 0; j < {1}; ++j) r[j][i] = a[i][j]; return r; }}\n", n, m);
    }
  for (int n = 2; n <= 4; ++n)
    for (int k = 2; k <= 4; ++k)
      for (int m = 2; m <= 4; ++m)
        out += fmt::format("double{0}x{2} mul(double{0}x{1} a, double{1}x{2} b) {{ double{0}x{2} r; for (int i = 0; i < {0}; ++i) "
                           "r[i] = mul(a[i], b); return r; }}\n", n, k, m);
  return out;
}

// The `[N]` after a declared name (`uniform vec4 planes[6];`), or "".
std::string array_suffix(const std::string& declaration, const std::string& name) {
  std::smatch m;
  if (std::regex_search(declaration, m, std::regex("\\b" + name + R"(\s*(\[\s*\w*\s*\]))"))) return std::regex_replace(m[1].str(), std::regex(R"(\s)"), "");
  return "";
}

// Replaces each call or index that `head` matches (from the match through the bracket closing the
// match's last opening bracket) with what `with` makes of the text inside those brackets.
void replace_bracketed(std::string& text, const std::regex& head, const std::function<std::string(const std::string&)>& with) {
  std::string out;
  size_t from = 0;
  std::smatch m;
  while (std::regex_search(text.cbegin() + static_cast<ptrdiff_t>(from), text.cend(), m, head)) {
    size_t at = from + static_cast<size_t>(m.position(0));
    size_t open = text.find_last_of("([", at + static_cast<size_t>(m.length(0)) - 1);
    char closer = text[open] == '(' ? ')' : ']';
    int depth = 0;
    size_t close = open;
    for (; close < text.size(); ++close) {
      if (text[close] == '(' || text[close] == '[') ++depth;
      if ((text[close] == ')' || text[close] == ']') && --depth == 0) break;
    }
    if (close >= text.size() || text[close] != closer) break;  // unbalanced: left to the compiler
    out += text.substr(from, at - from) + with(text.substr(open + 1, close - open - 1));
    from = close + 1;
  }
  text = out + text.substr(from);
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
void replace_texture_accesses(Lang lang, std::string& text, const std::string& name) {
  std::string texel = "lwc_texel_" + name;
  auto whole = [&](const std::string&) { return texel; };
  if (lang == Lang::hlsl) {
    replace_bracketed(text, std::regex("\\b" + name + R"(\s*\.\s*(Sample\w*|Load|Gather\w*)\s*\()"), whole);
    replace_bracketed(text, std::regex("\\b" + name + R"(\s*\[)"), whole);
    return;
  }
  replace_bracketed(text, std::regex(R"(\bimageStore\s*\(\s*)" + name + R"(\s*,)"), [&](const std::string& inside) {
    return "(" + texel + " = " + split_arguments(inside).back() + ")";
  });
  replace_bracketed(text, std::regex(R"(\b(texture\w*|texelFetch\w*|imageLoad)\s*\(\s*)" + name + R"(\s*,)"), whole);
}

}  // namespace

std::vector<std::string> enclosing_functions(Lang lang, const std::string& text, const std::vector<uint32_t>& offsets) {
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
        if (id >= 0) name = t.text(id);
      }
      c = t.at(c).first_child;
    }
    out.push_back(name);
  }
  return out;
}

std::string promote_to_double(Lang lang, const std::string& text) {
  std::string out;
  if (lang == Lang::hlsl) {
    out = std::regex_replace(text, std::regex(R"(\b(?:float|half|min16float)([1-4](?:x[1-4])?)?\b)"), "double$1");
  } else {
    out = std::regex_replace(text, std::regex(R"(\bfloat\b)"), "double");
    out = std::regex_replace(out, std::regex(R"(\bvec([2-4])\b)"), "dvec$1");
    out = std::regex_replace(out, std::regex(R"(\bmat([2-4](?:x[2-4])?)\b)"), "dmat$1");
  }
  // No precision statements for double.
  out = std::regex_replace(out, std::regex(R"(\bprecision\s+\w+\s+double\s*;)"), "");
  // Transcendentals have no double form on the GPU: they run in float32 (on small values, as a rule).
  return std::regex_replace(out, std::regex(R"(\b(sin|cos|tan|asin|acos|atan|pow|exp|log|exp2|log2)\s*\()"), "lwc_f32_$1(");
}

HarnessKernel build_harness_kernel(Lang lang, const std::string& input_text, const std::string& function, bool float64) {
  HarnessKernel k;
  // `#version` comes from the kernel; blank it (offsets unchanged).
  std::string text = std::regex_replace(input_text, std::regex(R"((^|\n)[ \t]*#[ \t]*version[^\n]*)"), "$1");
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
  bool glsl_main = lang == Lang::glsl && function == "main";

  // The declarations: kept functions and types as written, environment globals made private.
  std::string decl;
  static const std::regex glsl_qualifiers(
      R"(\blayout\s*\([^)]*\)|\b(uniform|in|out|inout|varying|attribute|flat|smooth|noperspective|centroid|invariant|readonly|writeonly|coherent|volatile|restrict)\b)");
  static const std::regex buffer(R"(^\s*(RW)?(?:Structured)?Buffer\s*<\s*(\w+)\s*>\s*(\w+))");
  static const std::regex resource(R"(^\s*(?:RW)?(Texture|Sampler|sampler|texture|image|ByteAddressBuffer|AppendStructuredBuffer|ConsumeStructuredBuffer))");
  static const std::regex hlsl_texture(R"(^\s*(RW)?Texture\w*\s*(?:<\s*(\w+)\s*>)?\s+\w)");
  static const std::regex hlsl_sampler(R"(^\s*(SamplerState|SamplerComparisonState|sampler\w*)\b)");
  static const std::regex glsl_texture(R"(\b([iu]?)(sampler|image)\w*\s+\w+\s*;)");
  std::vector<std::string> textures;  // globals whose accesses become `lwc_texel_NAME`
  std::vector<std::pair<std::string, std::string>> runtime_arrays;  // `x[]` block members: pattern, x[0]
  std::vector<std::pair<std::string, std::string>> env_inputs, env_outputs;  // name, type
  auto global_text = [&](const Global& g) -> std::string {
    std::string original = slice(text, g.node);
    std::smatch m;
    if (lang == Lang::hlsl) {
      if (std::regex_search(original, m, buffer)) {
        env_inputs.push_back({m[3].str() + "[0]", m[2]});
        if (m[1].matched) env_outputs.push_back({m[3].str() + "[0]", m[2]});
        return fmt::format("static {} {}[1];", m[2].str(), m[3].str());
      }
      if (std::regex_search(original, m, hlsl_texture)) {
        std::string type = m[2].matched ? m[2].str() : float64 ? "double4" : "float4";
        textures.push_back(g.name);
        env_inputs.push_back({"lwc_texel_" + g.name, type});
        if (m[1].matched) env_outputs.push_back({"lwc_texel_" + g.name, type});
        return fmt::format("static {} lwc_texel_{};", type, g.name);
      }
      if (std::regex_search(original, hlsl_sampler)) return "";  // only ever an argument of the samples replaced
      if (std::regex_search(original, m, resource)) {
        k.problem = fmt::format("`{}` is a texture or sampler: not filled by the harness", g.name);
        return "";
      }
      std::string masked_decl = slice(masked, g.node);
      static const std::regex constant(R"(^\s*(static|const)\b)");
      if (std::regex_search(masked_decl, constant)) return masked_decl;
      env_inputs.push_back({g.name, g.type + array_suffix(original, g.name)});
      return "static " + masked_decl;
    }
    if (auto block = blocks.find(g.node); block != blocks.end()) {
      const Block& b = block->second;
      // Runtime-sized arrays hold one element: every index of them reads element 0.
      std::string members = std::regex_replace(b.members, std::regex(R"(\[\s*\])"), "[1]");
      std::string text_out;
      if (b.instance.empty()) {
        for (const Global& member : globals)
          if (member.node == g.node) {
            env_inputs.push_back({member.name, member.type});
            if (b.writable) env_outputs.push_back({member.name, member.type});
            if (member.type.ends_with("[]")) runtime_arrays.push_back({member.name, member.name + "[0]"});
          }
        return members;
      }
      env_inputs.push_back({b.instance, g.type});
      if (b.writable) env_outputs.push_back({b.instance, g.type});
      for (const Field& f : structs[g.type])
        if (f.type.ends_with("[]")) runtime_arrays.push_back({b.instance + R"(\s*\.\s*)" + f.name, b.instance + "." + f.name + "[0]"});
      return fmt::format("struct {} {{{}}};\n{} {};", g.type, members, g.type, b.instance);
    }
    if (std::regex_search(original, m, glsl_texture)) {
      std::string kind = m[1].str(), type = kind == "i" ? "ivec4" : kind == "u" ? "uvec4" : float64 ? "dvec4" : "vec4";
      textures.push_back(g.name);
      env_inputs.push_back({"lwc_texel_" + g.name, type});
      if (m[2] == "image") env_outputs.push_back({"lwc_texel_" + g.name, type});
      return fmt::format("{} lwc_texel_{};", type, g.name);
    }
    static const std::regex constant(R"(^\s*const\b)"), stage_output(R"(\b(out|varying)\b)");
    if (std::regex_search(original, constant)) return original;
    bool output = std::regex_search(original, stage_output);
    (output ? env_outputs : env_inputs).push_back({g.name, g.type + array_suffix(original, g.name)});
    return std::regex_replace(original, glsl_qualifiers, "");
  };
  for (size_t i = 0; i < top.size(); ++i) {
    int c = top[i];
    uint32_t gap_begin = i ? t.at(top[i - 1]).end : 0;
    std::string gap = text.substr(gap_begin, t.at(c).begin - gap_begin);
    std::string item;
    bool keep = true;
    if (t.is(c, "function_definition")) {
      int id = declared_identifier(t, t.child_by_field(c, "declarator"));
      std::string name = id >= 0 ? std::string(t.text(id)) : "";
      keep = needed.count(name) > 0;
      item = slice(text, c);
      if (keep && glsl_main && name == "main")
        item.replace(t.at(id).begin - t.at(c).begin, 4, "lwc_entry");
      // Blocks come before the functions that use them: their runtime-sized arrays are known.
      for (const auto& array : runtime_arrays)
        replace_bracketed(item, std::regex("\\b" + array.first + R"(\s*\[)"), [&](const std::string&) { return array.second; });
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
    } else {
      item = slice(text, c);
    }
    // Other text before an item (an HLSL attribute such as [numthreads(..)]) goes with it.
    if (keep || blank(gap)) decl += gap;
    if (keep) decl += item;
  }
  if (!k.problem.empty()) return k;
  for (const std::string& name : textures) replace_texture_accesses(lang, decl, name);


  // GLSL stage built-ins become private globals.
  static const std::map<std::string, std::pair<std::string, bool>> builtins = {
      {"gl_Position", {"vec4", true}}, {"gl_PointSize", {"float", true}}, {"gl_FragCoord", {"vec4", false}},
      {"gl_VertexID", {"int", false}}, {"gl_InstanceID", {"int", false}}, {"gl_FrontFacing", {"bool", false}}};
  std::string prefix;
  if (lang == Lang::glsl)
    for (const auto& [name, info] : builtins) {
      std::regex word("\\b" + name + "\\b");
      if (!std::regex_search(decl, word)) continue;
      decl = std::regex_replace(decl, word, "lwc_" + name);
      std::string type = float64 ? promote_to_double(lang, info.first) : info.first;
      prefix += type + " lwc_" + name + ";\n";
      (info.second ? env_outputs : env_inputs).push_back({"lwc_" + name, type});
    }
  if (float64) {
    // float32 transcendentals for the double reference (see promote_to_double).
    std::string d = "double", f = "float";
    std::string v = lang == Lang::hlsl ? "double" : "dvec", fv = lang == Lang::hlsl ? "float" : "vec";
    for (const char* fn : {"sin", "cos", "tan", "asin", "acos", "atan", "exp", "log", "exp2", "log2"}) {
      prefix += fmt::format("{0} lwc_f32_{1}({0} x) {{ return {0}({1}({2}(x))); }}\n", d, fn, f);
      for (int n = 2; n <= 4; ++n) prefix += fmt::format("{0}{3} lwc_f32_{1}({0}{3} x) {{ return {0}{3}({1}({2}{3}(x))); }}\n", v, fn, fv, n);
    }
    prefix += fmt::format("{0} lwc_f32_pow({0} x, {0} y) {{ return {0}(pow({1}(x), {1}(y))); }}\n", d, f);
    for (int n = 2; n <= 4; ++n)
      prefix += fmt::format("{0}{2} lwc_f32_pow({0}{2} x, {0}{2} y) {{ return {0}{2}(pow({1}{2}(x), {1}{2}(y))); }}\n", v, fv, n);
    if (lang == Lang::hlsl) prefix += hlsl_double_matrix_functions();
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
  auto add_inputs = [&](const std::string& type, const std::string& path, const std::string& name) {
    if (!collect_leaves(structs, type, path, name, "", k.inputs, in_offset))
      k.problem = fmt::format("`{}` has type `{}`, which the harness cannot fill", name, type);
  };
  auto add_outputs = [&](const std::string& type, const std::string& path, const std::string& name) {
    if (!collect_leaves(structs, type, path, name, "", k.outputs, out_offset))
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
      static const std::regex writes(R"(^\s*(out|inout)\b)"), only_writes(R"(^\s*out\b)");
      bool out = std::regex_search(original, writes);
      bool in = !std::regex_search(original, only_writes);
      std::string local = fmt::format("lwc_p{}", index++);
      body += fmt::format("\t{} {};\n", ptype, local);
      if (in) add_inputs(ptype, local, pname);
      if (out) add_outputs(ptype, local, pname);
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
  std::string fill;
  for (const Leaf& l : k.inputs) assign(l, lang, float64, fill);
  std::string read;
  for (const Leaf& l : k.outputs) write(l, float64, read);
  k.body = body + fill + call_statement + read;
  k.in_stride = std::max(in_offset, 1);
  k.out_stride = std::max(out_offset, 1);
  if (k.outputs.empty() && k.problem.empty()) k.problem = fmt::format("`{}` has no result to compare (no return value, out parameter or stage output)", function);
  return k;
}

}  // namespace lwc
