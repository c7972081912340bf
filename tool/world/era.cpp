#include "world/era.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <cctype>
#include <stdexcept>

#include "lang/lexer.h"
#include "world/pattern.h"

namespace lwc {

std::optional<UnrealEra> parse_unreal_era(std::string_view s) {
  if (s == "4" || s.rfind("4.", 0) == 0) return UnrealEra::ue4;
  if (s.rfind("5.", 0) != 0 || s.size() < 3 || !std::isdigit(static_cast<unsigned char>(s[2]))) return std::nullopt;
  size_t end = 2;
  while (end < s.size() && std::isdigit(static_cast<unsigned char>(s[end]))) ++end;
  if (end != s.size()) return std::nullopt;
  int minor = std::stoi(std::string(s.substr(2)));
  return minor < 4 ? UnrealEra::ue5_0 : UnrealEra::ue5_4;
}

std::string_view era_name(UnrealEra era) {
  switch (era) {
    case UnrealEra::ue4: return "UE4";
    case UnrealEra::ue5_0: return "UE 5.0-5.3";
    case UnrealEra::ue5_4: return "UE 5.4+";
  }
  return "UE 5.4+";
}

UnrealEra infer_unreal_era(std::string_view text) {
  bool tile_offset = false, double_float = false;
  std::shared_ptr<const LexResult> lexed = lex(text);
  const std::vector<Token>& tokens = lexed->tokens;
  for (size_t i = 0; i < tokens.size(); ++i) {
    // Only names that start with F, L, M, D or P can say anything (the check below is the slow part).
    if (tokens[i].kind != Tok::ident || !std::strchr("FLMDP", text[tokens[i].begin])) continue;
    std::string_view w = text.substr(tokens[i].begin, tokens[i].end - tokens[i].begin);
    bool call = i + 1 < tokens.size() && text[tokens[i + 1].begin] == '(';
    auto named = [&](std::string_view prefix) {
      return w.size() > prefix.size() && w.rfind(prefix, 0) == 0 && std::isupper(static_cast<unsigned char>(w[prefix.size()]));
    };
    if (w.rfind("FLWC", 0) == 0 || (call && (named("LWC") || named("MakeLWC")))) tile_offset = true;
    if (w.rfind("FDF", 0) == 0 || w == "PrimaryView" || (call && (named("DF") || named("MakeDF")))) double_float = true;
  }
  if (tile_offset) return UnrealEra::ue5_0;
  return double_float ? UnrealEra::ue5_4 : UnrealEra::ue4;
}

bool is_unreal_source(std::string_view path, std::string_view text) {
  if (path.ends_with(".usf") || path.ends_with(".ush")) return true;
  return text.find("\"/Engine/") != std::string_view::npos;
}

namespace {

// The engine an #if condition selects when true: UE4, UE5 (as 5.0), or nothing it says.
std::optional<UnrealEra> condition_era(std::string_view keyword, std::string_view condition) {
  bool negated = keyword == "ifndef";
  // A comment after the condition is not part of it; nor is a CRLF file's '\r'.
  condition = condition.substr(0, std::min(condition.find("//"), condition.find("/*")));
  std::string c;
  for (char ch : condition)
    if (!std::isspace(static_cast<unsigned char>(ch)) && ch != '(' && ch != ')') c += ch;
  if (c.rfind("!", 0) == 0) {
    negated = !negated;
    c.erase(0, 1);
  }
  std::optional<UnrealEra> era;
  if (c.rfind("ENGINE_MAJOR_VERSION", 0) == 0) {
    std::string_view rest = std::string_view(c).substr(20);
    if (rest == "==4" || rest == "<5" || rest == "<=4") era = UnrealEra::ue4;
    else if (rest == "==5" || rest == ">=5" || rest == ">4") era = UnrealEra::ue5_0;
  } else if (std::all_of(c.begin(), c.end(), [](char ch) { return ident_char(ch); })) {
    // Hardware tessellation left the engine in UE 5.0: no UE5 build defines its switch.
    if (c.find("UE4") != std::string::npos || c == "USING_TESSELLATION") era = UnrealEra::ue4;
    else if (c.find("UE5") != std::string::npos) era = UnrealEra::ue5_0;
  }
  if (era && negated) era = *era == UnrealEra::ue4 ? UnrealEra::ue5_0 : UnrealEra::ue4;
  return era;
}

}  // namespace

std::vector<EraArm> era_guarded_arms(std::string_view text) {
  struct Open {
    std::optional<UnrealEra> era;  // of the first arm
    uint32_t arm_begin;
    int arm = 0;
  };
  std::vector<EraArm> out;
  std::vector<Open> stack;
  std::shared_ptr<const LexResult> lexed = lex(text);
  for (const Token& t : lexed->tokens) {
    if (t.kind != Tok::directive) continue;
    Directive d = read_directive(text.substr(t.begin, t.end - t.begin));
    auto close_arm = [&](Open& g) {
      if (!g.era) return;
      UnrealEra era = g.arm == 0 ? *g.era : (*g.era == UnrealEra::ue4 ? UnrealEra::ue5_0 : UnrealEra::ue4);
      out.push_back({g.arm_begin, t.begin, era});
    };
    if (d.keyword == "if" || d.keyword == "ifdef" || d.keyword == "ifndef") {
      stack.push_back({condition_era(d.keyword, d.rest), t.end});
    } else if ((d.keyword == "elif" || d.keyword == "else") && !stack.empty()) {
      Open& g = stack.back();
      close_arm(g);
      if (d.keyword == "elif") g.era.reset();  // an #elif chain says more than one engine: not read
      ++g.arm;
      g.arm_begin = t.end;
    } else if (d.keyword == "endif" && !stack.empty()) {
      close_arm(stack.back());
      stack.pop_back();
    }
  }
  return out;
}

std::string UnrealTarget::describe() const {
  std::string out(era_name(era));
  if (inferred) out += " (inferred from the code it uses; set \"unreal\" in .lwcport.json to name the engine the project builds against)";
  return out;
}

UnrealApi UnrealApi::load(const nlohmann::json& table) {
  UnrealApi api;
  for (const auto& [setting, names] : table.items()) {
    if (setting == "description") continue;
    if (setting == "shapes") {
      for (const auto& g : names) api.shapes_.insert(g.get<std::string>());
      continue;
    }
    auto era = parse_unreal_era(setting);
    if (!era) throw std::runtime_error("rules/world-space.json: unreal-api: unknown era " + setting);
    for (const auto& n : names) {
      auto [it, inserted] = api.first_.emplace(n.get<std::string>(), *era);
      if (!inserted && static_cast<int>(*era) < static_cast<int>(it->second)) it->second = *era;
    }
  }
  return api;
}

std::optional<UnrealEra> UnrealApi::first_era(std::string_view name) const {
  auto it = first_.find(name);
  if (it == first_.end()) return std::nullopt;
  return it->second;
}

bool UnrealApi::looks_like_api(std::string_view name) const {
  for (const std::string& g : shapes_)
    if (glob_match(g, name)) return true;
  return false;
}

}  // namespace lwc
