#include "project/config.h"

#include "shaderlib/engine_standins.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rules/rule.h"
#include "world/pattern.h"

namespace fs = std::filesystem;

namespace lwc {

namespace {

// Glob over path segments: `*` and `?` stay inside a segment, `**` spans any number of them.
bool match_segments(const std::vector<std::string>& pat, size_t p, const std::vector<std::string>& path, size_t s) {
  if (p == pat.size()) return s == path.size();
  if (pat[p] == "**") {
    for (size_t k = s; k <= path.size(); ++k)
      if (match_segments(pat, p + 1, path, k)) return true;
    return false;
  }
  return s < path.size() && glob_match(pat[p], path[s]) && match_segments(pat, p + 1, path, s + 1);
}

std::vector<std::string> split(std::string_view text) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= text.size()) {
    size_t slash = text.find('/', start);
    if (slash == std::string_view::npos) slash = text.size();
    if (slash > start) out.emplace_back(text.substr(start, slash - start));
    start = slash + 1;
  }
  return out;
}

}  // namespace

bool gitignore_match(std::string_view pattern, std::string_view relative, bool is_dir) {
  if (pattern.empty() || pattern[0] == '#') return false;
  bool dir_only = pattern.back() == '/';
  if (dir_only) pattern.remove_suffix(1);
  if (dir_only && !is_dir) return false;
  bool anchored = pattern.find('/') != std::string_view::npos;
  if (!pattern.empty() && pattern[0] == '/') pattern.remove_prefix(1);
  std::vector<std::string> pat = split(pattern), path = split(relative);
  if (!anchored) pat.insert(pat.begin(), "**");  // a bare name matches at any depth
  return match_segments(pat, 0, path, 0);
}

ProjectConfig ProjectConfig::parse(const fs::path& file, const std::string& text) {
  auto fail = [&](const std::string& what) { throw std::runtime_error(fmt::format("{}: {}", file.string(), what)); };
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    fail(fmt::format("invalid JSON at byte {}: {}", e.byte, e.what()));
  }
  if (!j.is_object()) fail("the config must be a JSON object");
  ProjectConfig c;
  c.dir = file.parent_path();
  // An absolute folder outside the project is one machine's layout: elsewhere (CI, a colleague)
  // it is missing and includes from it go unresolved. A relative one travels with the project.
  auto machine_specific = [&](const std::string& folder) -> std::string {
    fs::path p(folder);
    if (!p.is_absolute()) return "";
    std::string rel = p.lexically_normal().lexically_relative(fs::absolute(c.dir).lexically_normal()).generic_string();
    if (!rel.empty() && !rel.starts_with("..")) return "";
    return "is an absolute path outside the project: on another machine or in CI it may not be there; name it relative to the "
           "project's folder";
  };
  auto strings = [&](const char* key) {
    std::vector<std::string> out;
    if (!j.contains(key)) return out;
    if (!j.at(key).is_array()) fail(fmt::format("\"{}\" must be an array of strings", key));
    for (const auto& v : j.at(key)) {
      if (!v.is_string()) fail(fmt::format("\"{}\" must be an array of strings", key));
      out.push_back(v.get<std::string>());
    }
    return out;
  };
  auto known_rule = [&](const std::string& id) {
    if (!find_rule(id)) fail(fmt::format("unknown rule id \"{}\"", id));
  };
  for (const auto& item : j.items()) {
    static const char* known[] = {"severity", "select", "ignore", "include-dirs", "virtual-roots", "exclude", "world-sources", "max-file-bytes", "max-parse-seconds", "macros", "unreal", "library-definitions", "extensions", "defines", "overrides", "force-includes", "help-uri-base", "host", "engine-shaders", "host-rebases"};
    const std::string& key = item.key();
    if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) == std::end(known))
      fail(fmt::format("unknown key \"{}\"", key));
  }
  if (j.contains("severity")) {
    if (!j.at("severity").is_object()) fail("\"severity\" must map rule ids to note|warning|error");
    for (auto& [id, level] : j.at("severity").items()) {
      known_rule(id);
      Severity s{};
      if (!level.is_string() || !parse_severity(level.get<std::string>(), s))
        fail(fmt::format("severity of \"{}\" must be note, warning or error", id));
      c.severity[id] = s;
    }
  }
  c.select = strings("select");
  c.ignore = strings("ignore");
  for (const auto& id : c.select) known_rule(id);
  for (const auto& id : c.ignore) known_rule(id);
  for (const auto& d : strings("include-dirs")) {
    c.include_dirs.push_back(c.dir / d);
    std::error_code ec;
    if (!fs::is_directory(c.include_dirs.back(), ec))
      c.warnings.push_back(fmt::format("include dir \"{}\" is not a folder here ({}); includes are not looked for in it", d,
                                       c.include_dirs.back().lexically_normal().string()));
    else if (fs::weakly_canonical(c.include_dirs.back(), ec) == fs::path("/"))
      c.warnings.push_back(fmt::format("include dir \"{}\" is the file system's root: every include is looked for in all of it", d));
    else if (std::string why = machine_specific(d); !why.empty())
      c.warnings.push_back(fmt::format("include dir \"{}\" {}", d, why));
  }
  if (j.contains("virtual-roots")) {
    if (!j.at("virtual-roots").is_object()) fail("\"virtual-roots\" must map prefixes such as \"/Engine/\" to folders");
    for (auto& [prefix, folder] : j.at("virtual-roots").items()) {
      if (!folder.is_string() || folder.get<std::string>().empty()) fail(fmt::format("virtual root \"{}\" must name a folder", prefix));
      if (prefix.empty() || prefix.front() != '/' || prefix.back() != '/')
        fail(fmt::format("virtual root \"{}\": a prefix starts and ends with '/' (\"/Engine/\")", prefix));
      // A plugin's engine lives outside the plugin: "../../../Shaders/" is a normal folder here.
      c.virtual_roots.emplace_back(prefix, c.dir / folder.get<std::string>());
      std::error_code ec;
      if (!fs::is_directory(c.virtual_roots.back().second, ec))
        c.warnings.push_back(fmt::format("virtual root \"{}\" is not a folder here ({}); includes under it are not found", prefix,
                                         c.virtual_roots.back().second.lexically_normal().string()));
      else if (std::string why = machine_specific(folder.get<std::string>()); !why.empty())
        c.warnings.push_back(fmt::format("virtual root \"{}\" {}", prefix, why));
    }
  }
  c.exclude = strings("exclude");
  for (const auto& p : c.exclude) {
    if (p.empty() || p == "!") fail("\"exclude\" holds an empty pattern");
    for (const auto& part : fs::path(p))
      if (part == "..") fail(fmt::format("exclude pattern \"{}\" can match nothing: patterns are relative to the project's folder, and \"..\" leaves it", p));
  }
  if (j.contains("host-rebases")) {
    if (!j.at("host-rebases").is_boolean()) fail("\"host-rebases\" must be true or false");
    c.host_rebases = j.at("host-rebases").get<bool>();
  }
  if (j.contains("world-sources")) {
    c.world_sources = j.at("world-sources");
    if (!c.world_sources.is_array()) fail("\"world-sources\" must be an array of {\"match\", \"kind\"}");
    for (size_t i = 0; i < c.world_sources.size(); ++i) {
      const auto& s = c.world_sources[i];
      auto bad = [&](const std::string& why) { fail(fmt::format("world-sources[{}]: {}", i, why)); };
      if (!s.is_object() || !s.contains("match") || !s.contains("kind")) bad("needs a \"match\" pattern and a \"kind\"");
      for (auto& [key, value] : s.items()) {
        (void)value;
        if (key != "match" && key != "kind" && key != "languages" && key != "by-name")
          bad(fmt::format("unknown key \"{}\" (known: match, kind, languages, by-name)", key));
      }
      if (!s.at("match").is_string() || s.at("match").get<std::string>().empty())
        bad("\"match\" must be a non-empty path pattern such as \"View.WorldCameraOrigin\" or \"*.CameraPos\"");
      if (std::string why = PathPattern(s.at("match").get<std::string>()).problem(); !why.empty())
        bad(fmt::format("\"match\" {} can match nothing: {}", s.at("match").dump(), why));
      if (!s.at("kind").is_string() || !parse_kind(s.at("kind").get<std::string>()))
        bad(fmt::format("unknown world-space kind {}", s.at("kind").dump()));
      if (s.contains("languages")) {
        const auto& langs = s.at("languages");
        if (!langs.is_array() || langs.empty()) bad("\"languages\" must be a non-empty array of \"hlsl\" and \"glsl\"");
        for (const auto& l : langs)
          if (!l.is_string() || (l != "hlsl" && l != "glsl")) bad(fmt::format("unknown language {} (hlsl or glsl)", l.dump()));
      }
      if (s.contains("by-name") && !s.at("by-name").is_boolean() && s.at("by-name") != "plain")
        bad("\"by-name\" must be true, false or \"plain\"");
    }
  }
  if (j.contains("max-file-bytes")) {
    if (!j.at("max-file-bytes").is_number_unsigned() || j.at("max-file-bytes").get<size_t>() == 0)
      fail("\"max-file-bytes\" must be a positive integer (bytes; the default is 16 MiB)");
    c.max_file_bytes = j.at("max-file-bytes").get<size_t>();
  }
  if (j.contains("max-parse-seconds")) {
    const auto& v = j.at("max-parse-seconds");
    if (!v.is_number() || v.get<double>() <= 0 || v.get<double>() > 86400)
      fail("\"max-parse-seconds\" must be a number of seconds above 0 (the default is 30)");
    c.max_parse_seconds = v.get<double>();
  }
  if (j.contains("help-uri-base")) {
    const auto& v = j.at("help-uri-base");
    if (!v.is_string() || v.get<std::string>().empty())
      fail("\"help-uri-base\" must be the address the rule pages are under (lwcport appends \"<rule-id>.md\")");
    c.help_uri_base = v.get<std::string>();
    if (c.help_uri_base.back() != '/') c.help_uri_base += '/';
  }
  if (j.contains("macros")) add_macros(j.at("macros"), file.string(), c.macros);
  if (j.contains("host")) {
    if (!j.at("host").is_object()) fail("\"host\" must be an object (additions to rules/host-world.json: docs/host.md)");
    c.host = j.at("host");
  }
  if (j.contains("unreal")) {
    const auto& u = j.at("unreal");
    c.unreal = u.is_string() ? parse_unreal_era(u.get<std::string>()) : std::nullopt;
    if (!c.unreal) fail("\"unreal\" must name the engine version the project builds against: \"4\", \"5.0\" (to 5.3) or \"5.4\" (and later)");
  }
  if (j.contains("engine-shaders")) {
    const auto& e = j.at("engine-shaders");
    if (!e.is_string() || e.get<std::string>().empty()) fail("\"engine-shaders\" must name the engine's Shaders folder (\"../../Engine/Shaders\")");
    c.engine_shaders = c.dir / e.get<std::string>();
    std::string shown = c.engine_shaders->lexically_normal().string();
    c.engine_era = engine_shaders_era(*c.engine_shaders);
    if (!c.engine_era)
      c.warnings.push_back(fmt::format("\"engine-shaders\" is not an engine Shaders folder here ({} holds no Private/Common.ush); "
                                       "builds are checked against lwcport's stub instead", shown));
    else if (std::string why = machine_specific(e.get<std::string>()); !why.empty())
      c.warnings.push_back(fmt::format("\"engine-shaders\" {}", why));
    if (c.engine_era && c.unreal && *c.unreal != *c.engine_era)
      c.warnings.push_back(fmt::format("\"engine-shaders\" holds {}'s headers but \"unreal\" says {}: builds are checked against the "
                                       "headers, findings follow \"unreal\"", era_name(*c.engine_era), era_name(*c.unreal)));
    if (c.engine_era && !c.unreal) c.unreal = c.engine_era;  // the engine says what the project builds against
    // Its includes resolve as the engine's do, unless the project maps /Engine/ itself.
    bool mapped = std::any_of(c.virtual_roots.begin(), c.virtual_roots.end(), [](const auto& r) { return r.first == "/Engine/"; });
    if (c.engine_era && !mapped) c.virtual_roots.emplace_back("/Engine/", *c.engine_shaders);
  }
  if (j.contains("extensions")) {
    if (!j.at("extensions").is_object()) fail("\"extensions\" must map extensions such as \".fxh\" to hlsl, glsl, glsl-in-js or none");
    for (auto& [ext, format] : j.at("extensions").items()) {
      if (!format.is_string()) fail(fmt::format("extension \"{}\": the format must be a string", ext));
      c.formats.set(ext, format.get<std::string>(), file.string());
    }
  }
  // `{"NAME": "value"}`: a value is a string, a number or a boolean (1 or 0), as -D takes it.
  auto defines = [&](const nlohmann::json& d, const std::string& where) {
    Defines out;
    if (!d.is_object()) fail(fmt::format("{} must map macro names to values (\"THREADGROUP_SIZE\": 8)", where));
    for (auto& [name, value] : d.items()) {
      bool identifier = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0]));
      for (char ch : name) identifier &= std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
      if (!identifier) fail(fmt::format("{}: \"{}\" is not a macro name", where, name));
      if (!value.is_string() && !value.is_boolean() && !value.is_number())
        fail(fmt::format("{}: the value of \"{}\" must be a string, a number or a boolean", where, name));
      std::string text = value.is_string() ? value.get<std::string>() : value.is_boolean() ? (value.get<bool>() ? "1" : "0") : value.dump();
      if (text.find('\n') != std::string::npos) fail(fmt::format("{}: the value of \"{}\" holds a line break", where, name));
      out.emplace_back(name, text);
    }
    return out;
  };
  if (j.contains("defines")) c.defines = defines(j.at("defines"), "\"defines\"");
  if (j.contains("overrides")) {
    const auto& list = j.at("overrides");
    if (!list.is_array()) fail("\"overrides\" must be an array of {\"files\": [patterns], \"defines\": {...}}");
    for (size_t i = 0; i < list.size(); ++i) {
      std::string where = fmt::format("overrides[{}]", i);
      const auto& o = list[i];
      if (!o.is_object() || !o.contains("files") || !o.contains("defines")) fail(where + " needs \"files\" and \"defines\"");
      for (auto& [key, value] : o.items()) {
        (void)value;
        if (key != "files" && key != "defines") fail(fmt::format("{}: unknown key \"{}\" (known: files, defines)", where, key));
      }
      PathDefines entry;
      if (!o.at("files").is_array() || o.at("files").empty()) fail(where + ": \"files\" must be a non-empty array of patterns");
      for (const auto& f : o.at("files")) {
        if (!f.is_string() || f.get<std::string>().empty()) fail(where + ": \"files\" must be a non-empty array of patterns");
        entry.files.push_back(f.get<std::string>());
      }
      entry.defines = defines(o.at("defines"), where + ".defines");
      c.overrides.push_back(std::move(entry));
    }
  }
  if (j.contains("force-includes")) {
    const auto& list = j.at("force-includes");
    auto bad = [&] { fail("\"force-includes\" must be an array of include names (\"/Engine/Private/Common.ush\")"); };
    if (!list.is_array()) bad();
    for (const auto& name : list) {
      if (!name.is_string() || name.get<std::string>().empty() || name.get<std::string>().find_first_of("\"\n") != std::string::npos) bad();
      c.force_includes.push_back(name.get<std::string>());
    }
  }
  if (j.contains("library-definitions")) {
    const auto& l = j.at("library-definitions");
    if (!l.is_string() || (l != "skip" && l != "lint")) fail("\"library-definitions\" must be \"skip\" (the default) or \"lint\"");
    c.lint_library = l == "lint";
  }
  return c;
}

std::vector<std::shared_ptr<const ProjectConfig>> ConfigFinder::loaded() {
  if (fixed_) return fixed_->dir.empty() ? std::vector<std::shared_ptr<const ProjectConfig>>{} : std::vector{fixed_};
  std::lock_guard lock(mutex_);
  std::vector<std::shared_ptr<const ProjectConfig>> out;
  for (const auto& [dir, config] : by_dir_)
    if (!config->dir.empty() && std::find(out.begin(), out.end(), config) == out.end()) out.push_back(config);
  return out;
}

bool ProjectConfig::excluded(const fs::path& path, bool is_dir) const {
  if (exclude.empty()) return false;
  std::string rel = fs::relative(path, dir.empty() ? fs::path(".") : dir).generic_string();
  if (rel.rfind("..", 0) == 0) return false;
  for (const auto& p : exclude)
    if (gitignore_match(p, rel, is_dir)) return true;
  return false;
}

ProjectConfig::Defines ProjectConfig::defines_for(const fs::path& file) const {
  Defines out = defines;
  if (overrides.empty()) return out;
  std::string rel = fs::relative(file, dir.empty() ? fs::path(".") : dir).generic_string();
  for (const PathDefines& o : overrides)
    if (std::any_of(o.files.begin(), o.files.end(), [&](const std::string& p) { return gitignore_match(p, rel, false); }))
      for (const auto& define : o.defines) {
        auto same = std::find_if(out.begin(), out.end(), [&](const auto& d) { return d.first == define.first; });
        if (same != out.end()) same->second = define.second;  // one definition each: glslang refuses a redefinition
        else out.push_back(define);
      }
  return out;
}

std::shared_ptr<const ProjectConfig> ConfigFinder::read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read");
  std::stringstream text;
  text << in.rdbuf();
  return std::make_shared<const ProjectConfig>(ProjectConfig::parse(fs::absolute(file).lexically_normal(), text.str()));
}

std::shared_ptr<const ProjectConfig> ConfigFinder::for_dir(const fs::path& start) {
  if (fixed_) return fixed_;
  std::error_code ec;
  fs::path dir = fs::absolute(start, ec).lexically_normal();
  std::lock_guard lock(mutex_);
  std::vector<fs::path> visited;
  std::shared_ptr<const ProjectConfig> found;
  for (fs::path d = dir;; d = d.parent_path()) {
    if (auto it = by_dir_.find(d); it != by_dir_.end()) {
      found = it->second;
      break;
    }
    visited.push_back(d);
    fs::path file = d / ".lwcport.json";
    if (fs::is_regular_file(file, ec)) {
      found = read(file);
      break;
    }
    if (d == d.parent_path() || d.empty()) {
      found = std::make_shared<const ProjectConfig>();
      break;
    }
  }
  for (const auto& d : visited) by_dir_[d] = found;
  return found;
}

AnalyzeOptions analysis_options(const ProjectConfig& config) {
  AnalyzeOptions a;
  a.select.insert(config.select.begin(), config.select.end());
  a.ignore.insert(config.ignore.begin(), config.ignore.end());
  a.severity = config.severity;
  a.world_sources = config.world_sources;
  a.macros = config.macros;
  a.unreal = config.unreal;
  a.lint_library = config.lint_library;
  a.host_rebases = config.host_rebases;
  a.formats = &config.formats;
  a.max_bytes = config.max_file_bytes;
  a.max_parse_seconds = config.max_parse_seconds;
  return a;
}

}  // namespace lwc
