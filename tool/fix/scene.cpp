#include "fix/scene.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "project/config.h"
#include "project/files.h"
#include "rules/rule.h"

namespace lwc {

namespace {

struct Unit {
  const char* name;
  double cm;
};
constexpr Unit kUnits[] = {{"mm", 0.1}, {"cm", 1.0}, {"uu", 1.0}, {"m", 100.0}, {"km", 100000.0}};

std::optional<double> parse_number(std::string_view s) {
  if (s.rfind("2^", 0) == 0) {
    auto e = parse_number(s.substr(2));
    if (!e || *e != std::floor(*e) || std::abs(*e) > 200) return std::nullopt;
    return std::ldexp(1.0, static_cast<int>(*e));
  }
  if (size_t slash = s.find('/'); slash != std::string_view::npos) {
    auto a = parse_number(s.substr(0, slash)), b = parse_number(s.substr(slash + 1));
    if (!a || !b || *b == 0) return std::nullopt;
    return *a / *b;
  }
  std::string copy(s);
  char* end = nullptr;
  double v = std::strtod(copy.c_str(), &end);
  if (copy.empty() || *end || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::string where(const std::string& path) { return path.empty() ? "scene" : path; }

double distance_value(const nlohmann::json& j, const char* key, const std::string& path) {
  auto bad = [&]() {
    return std::runtime_error(fmt::format("{}: \"{}\" must be a positive distance with a unit, e.g. \"100 km\", \"2^43 cm\", \"1 mm\"", where(path), key));
  };
  if (!j.is_string()) throw bad();
  auto v = parse_distance(j.get<std::string>());
  if (!v || *v <= 0) throw bad();
  return *v;
}

void read_numbers(const nlohmann::json& j, const std::string& path, std::optional<double>& extent,
                  std::optional<double>& view, std::optional<double>& precision) {
  if (j.contains("world-extent")) extent = distance_value(j.at("world-extent"), "world-extent", path);
  if (j.contains("view-distance")) view = distance_value(j.at("view-distance"), "view-distance", path);
  if (j.contains("precision")) precision = distance_value(j.at("precision"), "precision", path);
}

}  // namespace

std::optional<double> parse_distance(std::string_view text) {
  size_t b = text.find_first_not_of(" \t"), e = text.find_last_not_of(" \t");
  if (b == std::string_view::npos) return std::nullopt;
  text = text.substr(b, e - b + 1);
  size_t space = text.find_last_of(' ');
  if (space == std::string_view::npos) return std::nullopt;  // a unit is required
  std::string_view unit = text.substr(space + 1);
  std::string_view number = text.substr(0, text.find_last_not_of(' ', space) + 1);
  for (const Unit& u : kUnits) {
    if (unit != u.name) continue;
    auto v = parse_number(number);
    if (!v) return std::nullopt;
    return *v * u.cm;
  }
  return std::nullopt;
}

std::string format_distance(double cm) {
  int exponent = 0;
  if (cm >= 1048576.0 && std::frexp(cm, &exponent) == 0.5)
    return fmt::format("2^{} cm ({:.4g} km)", exponent - 1, cm / 100000.0);
  if (cm >= 100000.0) return fmt::format("{:.4g} km", cm / 100000.0);
  if (cm >= 100.0) return fmt::format("{:.4g} m", cm / 100.0);
  return fmt::format("{:.3g} cm", cm);
}

double float32_error(double magnitude) {
  if (!(magnitude > 0)) return 0;
  int exponent = static_cast<int>(std::floor(std::log2(magnitude)));
  return std::ldexp(1.0, exponent - 24);
}

std::optional<Strategy> parse_strategy(std::string_view name) {
  if (name == "auto") return Strategy::automatic;
  if (name == "translated") return Strategy::translated;
  if (name == "df") return Strategy::df;
  return std::nullopt;
}

SceneNumbers Scene::for_path(std::string_view path) const {
  SceneNumbers n = numbers;
  for (const SceneOverride& o : overrides) {
    bool match = false;
    for (const std::string& glob : o.paths) match = match || gitignore_match(glob, path, false);
    if (!match) continue;
    if (o.world_extent) n.world_extent = *o.world_extent;
    if (o.view_distance) n.view_distance = *o.view_distance;
    if (o.precision) n.precision = *o.precision;
  }
  return n;
}

Scene parse_scene(std::string_view text, const std::string& path) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports a byte offset; turn it into a line and column.
    size_t at = std::min<size_t>(e.byte ? e.byte - 1 : 0, text.size());
    int line = 1, column = 1;
    for (size_t i = 0; i < at; ++i) {
      if (text[i] == '\n') ++line, column = 1;
      else ++column;
    }
    throw std::runtime_error(fmt::format("{}:{}:{}: malformed scene profile (JSON): {}", where(path), line, column, e.what()));
  }
  if (!j.is_object()) throw std::runtime_error(where(path) + ": a scene profile is a JSON object");
  for (const auto& [key, value] : j.items()) {
    static const char* known[] = {"name", "description", "world-extent", "view-distance", "precision", "overrides"};
    if (std::find(std::begin(known), std::end(known), key) == std::end(known))
      throw std::runtime_error(fmt::format("{}: unknown key \"{}\" (known: name, description, world-extent, view-distance, precision, overrides)", where(path), key));
  }
  Scene scene;
  scene.name = j.value("name", path);
  std::optional<double> extent, view, precision;
  read_numbers(j, path, extent, view, precision);
  if (extent) scene.numbers.world_extent = *extent;
  if (view) scene.numbers.view_distance = *view;
  if (precision) scene.numbers.precision = *precision;
  for (const auto& o : j.value("overrides", nlohmann::json::array())) {
    SceneOverride so;
    if (!o.is_object() || !o.contains("paths") || !o.at("paths").is_array())
      throw std::runtime_error(where(path) + ": each override needs \"paths\": [globs]");
    for (const auto& g : o.at("paths")) so.paths.push_back(g.get<std::string>());
    read_numbers(o, path, so.world_extent, so.view_distance, so.precision);
    scene.overrides.push_back(std::move(so));
  }
  return scene;
}

Scene load_scene(const std::string& path) {
  ReadResult r = read_file(path, 1u << 20);
  if (!r.error.empty() || r.too_large)
    throw std::runtime_error(path + ": cannot read the scene profile: " + (r.too_large ? "over 1 MB" : r.error));
  return parse_scene(r.text, path);
}

namespace {

const Fix* candidate(const Finding& f, std::string_view strategy) {
  for (const Fix& fix : f.fixes)
    if (fix.strategy == strategy) return &fix;
  return nullptr;
}

}  // namespace

void plan_fixes(std::vector<Finding>& findings, const SceneNumbers& scene, Strategy strategy) {
  const double world_error = float32_error(scene.world_extent);
  const double view_error = float32_error(scene.view_distance);
  for (Finding& f : findings) {
    const RuleInfo* rule = find_rule(f.rule);
    if (!rule || !rule->scene_dependent) {
      // A forced strategy holds for every rule: translated-world's rewrite must not undo --strategy df.
      if (strategy != Strategy::automatic) {
        std::string forced = strategy == Strategy::translated ? "translated" : "df";
        std::erase_if(f.fixes, [&](const Fix& fix) { return !fix.strategy.empty() && fix.strategy != forced; });
      }
      if (f.fixes.size() > 1) f.fixes.resize(1);
      continue;
    }
    std::string numbers = fmt::format("float32 error at the world extent {} is {}", format_distance(scene.world_extent),
                                      format_distance(world_error));
    if (world_error <= scene.precision) {
      f.not_needed = true;
      f.severity = Severity::note;
      f.fixes.clear();
      f.decision = fmt::format("not needed: {}, within the precision target {}", numbers, format_distance(scene.precision));
      f.message = "not needed in this scene: " + f.message;
      continue;
    }
    const Fix* translated = candidate(f, "translated");
    const Fix* df = candidate(f, "df");
    const Fix* plain = candidate(f, "");
    bool translated_enough = view_error <= scene.precision;
    std::string need = translated_enough
                           ? fmt::format("translated world is enough (its float32 error at the view distance {} is {})",
                                         format_distance(scene.view_distance), format_distance(view_error))
                           : fmt::format("DoubleFloat is needed (translated world's float32 error at the view distance {} is {})",
                                         format_distance(scene.view_distance), format_distance(view_error));
    const Fix* chosen = nullptr;
    std::string why;
    if (strategy == Strategy::translated) {
      chosen = translated, why = "translated world, as --strategy translated asks";
    } else if (strategy == Strategy::df) {
      chosen = df, why = "DoubleFloat, as --strategy df asks";
    } else if (translated && translated_enough) {
      chosen = translated, why = "translated world, the cheaper rewrite";
    } else if (df) {
      chosen = df, why = translated ? "DoubleFloat" : "DoubleFloat: this value cannot be made camera-relative";
    }
    // A translated rewrite short of the target is never written: the site is left, and says why.
    if (translated && !translated_enough && !chosen)
      f.withheld.push_back(fmt::format("translated world: its float32 error at the view distance ({}) is over the precision "
                                       "target {}, and no DoubleFloat rewrite exists here", format_distance(view_error),
                                       format_distance(scene.precision)));
    if (!chosen && plain) chosen = plain, why = "the rule's rewrite";
    std::string none = "no automatic rewrite for this site";
    for (size_t i = 0; i < f.withheld.size(); ++i) none += (i ? "; " : " (") + f.withheld[i];
    if (!f.withheld.empty()) none += ")";
    f.decision = fmt::format("needed: {} > precision target {}; {}; {}", numbers, format_distance(scene.precision), need,
                             chosen ? "fix: " + why : none);
    if (chosen) {
      Fix keep = *chosen;
      f.fixes = {std::move(keep)};
    } else {
      f.fixes.clear();
    }
  }
}

}  // namespace lwc
