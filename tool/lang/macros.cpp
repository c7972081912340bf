#include "lang/macros.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "lang/lexer.h"
#include "lang/syntax.h"
#include "core/embedded.h"

namespace lwc {

namespace {

using namespace std::string_view_literals;

constexpr std::pair<MacroUse, std::string_view> kUseNames[] = {
    {MacroUse::qualifier, "qualifier"}, {MacroUse::attribute, "attribute"},     {MacroUse::suffix, "suffix"},
    {MacroUse::declaration, "declaration"}, {MacroUse::type, "type"}, {MacroUse::loop, "loop"},
};

// Words a qualifier macro may expand to (HLSL and GLSL).
constexpr std::array kQualifierWords = {
    "in"sv, "out"sv, "inout"sv, "uniform"sv, "static"sv, "const"sv, "precise"sv, "invariant"sv,
    "nointerpolation"sv, "linear"sv, "centroid"sv, "noperspective"sv, "sample"sv, "groupshared"sv,
    "row_major"sv, "column_major"sv, "snorm"sv, "unorm"sv, "globallycoherent"sv, "inline"sv,
    "highp"sv, "mediump"sv, "lowp"sv, "flat"sv, "smooth"sv, "volatile"sv};

bool is_qualifier_word(std::string_view w) {
  return std::find(kQualifierWords.begin(), kQualifierWords.end(), w) != kQualifierWords.end();
}

bool is_swizzle(std::string_view s) {
  return !s.empty() && s.size() <= 4 &&
         (s.find_first_not_of("xyzw") == std::string_view::npos || s.find_first_not_of("rgba") == std::string_view::npos);
}

// The body of a #define with comments and continuations turned into spaces.
std::string clean_body(std::string_view rest) {
  std::string out;
  for (size_t i = 0; i < rest.size(); ++i) {
    if (size_t after = continuation_end(rest, i); after != i) {
      out += ' ';
      i = after - 1;
      continue;
    }
    if (rest.compare(i, 2, "//") == 0) break;
    if (rest.compare(i, 2, "/*") == 0) {
      size_t end = rest.find("*/", i + 2);
      if (end == std::string_view::npos) break;
      out += ' ';
      i = end + 1;
      continue;
    }
    out += rest[i] == '\n' || rest[i] == '\r' || rest[i] == '\t' ? ' ' : rest[i];
  }
  size_t b = out.find_first_not_of(' '), e = out.find_last_not_of(' ');
  return b == std::string::npos ? std::string() : out.substr(b, e - b + 1);
}

std::optional<MacroUse> classify(bool function_like, const std::vector<std::string>& parameters, std::string_view body,
                                 const MacroTable& known, const MacroTable& learnt) {
  auto lookup = [&](std::string_view w) -> std::optional<MacroUse> {
    if (auto it = learnt.find(w); it != learnt.end()) return it->second;
    if (auto it = known.find(w); it != known.end()) return it->second;
    return std::nullopt;
  };
  if (!body.empty() && body[0] == '[') {
    // An attribute is the whole body: `[unroll]`, `[[vk::push_constant]]`. After one, a `for`
    // with the parameters as header is a loop; anything else (`[shader("raygeneration")] void
    // name()`) is a declaration the masker reads by its shape.
    size_t close = 0;
    for (int depth = 0; close < body.size(); ++close) {
      depth += body[close] == '[' ? 1 : body[close] == ']' ? -1 : 0;
      if (depth == 0) break;
    }
    std::string_view after = close < body.size() ? body.substr(close + 1) : std::string_view();
    while (!after.empty() && after[0] == ' ') after.remove_prefix(1);
    if (after.empty()) return MacroUse::attribute;
    if (function_like && after.rfind("for", 0) == 0) return classify(function_like, parameters, after, known, learnt);
    return std::nullopt;
  }
  // An optional parameter (`, in FIsFrontFace bIsFrontFace : SV_IsFrontFace`) reads as nothing.
  if (!function_like && !body.empty() && body[0] == ',') return MacroUse::qualifier;
  if (!function_like && body.size() > 1 && body[0] == '.' && is_swizzle(body.substr(1))) return MacroUse::suffix;
  std::vector<std::string_view> words;
  for (size_t i = 0; i < body.size();) {
    if (ident_start(body[i])) {
      size_t b = i;
      while (i < body.size() && ident_char(body[i])) ++i;
      words.push_back(body.substr(b, i - b));
    } else if (body[i] == ' ') {
      ++i;
    } else {
      words.clear();
      words.push_back({});  // not a plain word list
      break;
    }
  }
  if (function_like) {
    // `for (A; B; C)` made of the parameters: the header is written with commas at the call.
    if (body.rfind("for", 0) == 0 && body.size() > 3 && (body[3] == '(' || body[3] == ' ')) {
      size_t open = body.find('('), close = body.find(')');
      std::string header(body.substr(open + 1, close == std::string_view::npos ? 0 : close - open - 1));
      std::string want;
      for (const std::string& p : parameters) want += (want.empty() ? "" : ";") + p;
      header.erase(std::remove(header.begin(), header.end(), ' '), header.end());
      if (!parameters.empty() && header == want) return MacroUse::loop;
      return std::nullopt;
    }
    if (words.size() == 1 && !words[0].empty()) {
      if (auto use = lookup(words[0]); use && *use == MacroUse::attribute) return MacroUse::attribute;
    }
    // A body that is a known attribute macro called with the arguments: SUBSTRATE_UNROLL_N(X) UNROLL_N(X).
    size_t paren = body.find('(');
    if (paren != std::string_view::npos && paren > 0) {
      if (auto use = lookup(body.substr(0, paren)); use && *use == MacroUse::attribute) return MacroUse::attribute;
    }
    return std::nullopt;
  }
  if (words.empty()) return MacroUse::qualifier;
  bool qualifiers = true;
  for (std::string_view w : words) {
    if (w.empty()) return std::nullopt;
    auto use = lookup(w);
    if (!is_qualifier_word(w) && !(use && *use == MacroUse::qualifier)) qualifiers = false;
  }
  if (qualifiers) return MacroUse::qualifier;
  if (words.size() == 1) {
    if (auto use = lookup(words[0]); use && (*use == MacroUse::attribute || *use == MacroUse::suffix)) return *use;
  }
  return std::nullopt;
}

}  // namespace

std::optional<MacroUse> parse_macro_use(std::string_view name) {
  for (auto [use, n] : kUseNames)
    if (n == name) return use;
  return std::nullopt;
}

std::string_view macro_use_name(MacroUse use) {
  for (auto [u, n] : kUseNames)
    if (u == use) return n;
  return "qualifier";
}

void add_macros(const nlohmann::json& table, std::string_view where, MacroTable& into) {
  if (!table.is_object()) throw std::runtime_error(std::string(where) + ": \"macros\" must be an object of NAME: use");
  for (const auto& [name, use] : table.items()) {
    if (name.empty() || !ident_start(name[0]) || !std::all_of(name.begin(), name.end(), ident_char))
      throw std::runtime_error(std::string(where) + ": macro name \"" + name + "\" is not an identifier");
    auto u = use.is_string() ? parse_macro_use(use.get<std::string>()) : std::nullopt;
    if (!u)
      throw std::runtime_error(std::string(where) + ": macro " + name + ": use must be one of qualifier, attribute, " +
                               "suffix, declaration, type, loop (got " + use.dump() + ")");
    into[name] = *u;
  }
}

const MacroTable& known_macros(Lang lang) {
  static const auto tables = [] {
    std::array<MacroTable, 2> out;
    nlohmann::json data;
    for (const EmbeddedFile& f : embedded_rule_files())
      if (f.name == "macros.json") data = nlohmann::json::parse(f.text).at("macros");
    add_macros(data.at("hlsl"), "rules/macros.json", out[0]);
    add_macros(data.at("glsl"), "rules/macros.json", out[1]);
    return out;
  }();
  return tables[lang == Lang::hlsl ? 0 : 1];
}

void learn_macros(std::string_view text, const MacroTable& known, MacroTable& into) {
  // A #define can only appear at a line start, so a cheap scan finds every candidate line.
  for (size_t at = text.find('#'); at != std::string_view::npos; at = text.find('#', at + 1)) {
    size_t line = text.rfind('\n', at);
    line = line == std::string_view::npos ? 0 : line + 1;
    if (text.substr(line, at - line).find_first_not_of(" \t") != std::string_view::npos) continue;
    size_t end = at;
    while (end < text.size() && text[end] != '\n') {
      size_t after = continuation_end(text, end);
      end = after != end ? after : end + 1;
    }
    Directive d = read_directive(text.substr(at, end - at));
    if (d.keyword != "define") continue;
    std::string_view rest = d.rest;
    size_t i = rest.find_first_not_of(" \t");
    if (i == std::string_view::npos || !ident_start(rest[i])) continue;
    size_t b = i;
    while (i < rest.size() && ident_char(rest[i])) ++i;
    std::string name(rest.substr(b, i - b));
    bool function_like = i < rest.size() && rest[i] == '(';
    std::vector<std::string> parameters;
    if (function_like) {
      size_t close = rest.find(')', i);
      if (close == std::string_view::npos) continue;
      std::string list(rest.substr(i + 1, close - i - 1));
      for (size_t b = 0; b <= list.size();) {
        size_t e = std::min(list.find(',', b), list.size());
        std::string p = list.substr(b, e - b);
        p.erase(std::remove_if(p.begin(), p.end(), [](char c) { return c == ' ' || c == '\t'; }), p.end());
        if (!p.empty()) parameters.push_back(p);
        b = e + 1;
      }
      i = close + 1;
    }
    if (into.count(name) || known.count(name)) continue;
    if (auto use = classify(function_like, parameters, clean_body(rest.substr(i)), known, into)) into.emplace(std::move(name), *use);
  }
}

}  // namespace lwc
