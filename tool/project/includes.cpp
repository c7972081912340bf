#include "project/includes.h"

#include "core/fork_gate.h"

#include <algorithm>
#include <set>

#include "project/files.h"
#include "rules/analyze.h"

namespace fs = std::filesystem;

namespace lwc {

namespace {
constexpr int kMaxIncludeDepth = 16;

std::optional<fs::path> find_include(const std::string& include, const fs::path& from, const ProjectConfig& config) {
  std::error_code ec;
  for (const auto& [prefix, folder] : config.virtual_roots) {
    if (include.rfind(prefix, 0) == 0) {
      fs::path p = folder / include.substr(prefix.size());
      if (fs::is_regular_file(p, ec)) return p;
    }
  }
  // Unreal's virtual paths with no root configured: `/Engine/Private/X` and `/Plugin/Name/Private/X`
  // are `Private/X` under the nearest `Shaders` folder above the including file, as the engine
  // and each plugin lay out their shaders.
  if (include.rfind("/Engine/", 0) == 0 || include.rfind("/Plugin/", 0) == 0) {
    size_t rest = include.rfind("/Engine/", 0) == 0 ? 8 : include.find('/', 8);
    if (rest != std::string::npos) {
      for (fs::path dir = from.parent_path(); !dir.empty() && dir != dir.root_path(); dir = dir.parent_path()) {
        if (dir.filename() != "Shaders") continue;
        fs::path p = dir / include.substr(rest == 8 ? 8 : rest + 1);
        if (fs::is_regular_file(p, ec)) return p;
        break;
      }
    }
  }
  if (!include.empty() && include[0] != '/') {
    fs::path local = from.parent_path() / include;
    if (fs::is_regular_file(local, ec)) return local;
    for (const auto& dir : config.include_dirs) {
      fs::path p = dir / include;
      if (fs::is_regular_file(p, ec)) return p;
    }
  }
  return std::nullopt;
}

}  // namespace

bool engine_file(const fs::path& file, const ProjectConfig& config) {
  auto under = [&](const fs::path& dir) {
    std::error_code ec;
    fs::path root = fs::weakly_canonical(dir, ec);
    auto rel = file.lexically_relative(root);
    return !ec && !rel.empty() && *rel.begin() != "..";
  };
  for (const auto& [prefix, folder] : config.virtual_roots)
    if (prefix.rfind("/Engine/", 0) == 0 && under(folder)) return true;
  for (fs::path dir = file.parent_path(); !dir.empty() && dir != dir.root_path(); dir = dir.parent_path())
    if (std::error_code ec; dir.filename() == "Shaders" &&
                            (dir.parent_path().filename() == "Engine" || fs::is_regular_file(dir / "Private" / "Common.ush", ec)))
      return true;
  return false;
}

std::optional<fs::path> IncludeSummaries::resolve(const std::string& include, const fs::path& from,
                                                  const ProjectConfig& config) {
  // Resolution depends on the including folder only: cached per folder.
  auto key = std::make_tuple(&config, from.parent_path(), include);
  ForkSafeLock lock(mutex_);
  auto it = resolved_.find(key);
  if (it == resolved_.end()) it = resolved_.emplace(key, find_include(include, from, config)).first;
  return it->second;
}

fs::path IncludeSummaries::canonical(const fs::path& p) {
  ForkSafeLock lock(mutex_);
  auto it = canonical_.find(p);
  if (it != canonical_.end()) return it->second;
  std::error_code ec;
  fs::path c = fs::weakly_canonical(p, ec);
  return canonical_.emplace(p, ec ? p : c).first->second;
}

std::vector<fs::path> IncludeSummaries::resolve_all(const std::vector<std::string>& includes, const fs::path& from,
                                                    const ProjectConfig& config) {
  std::vector<fs::path> out;
  for (const std::string& inc : includes)
    if (auto file = resolve(inc, from, config)) out.push_back(canonical(*file));
  return out;
}

ReadResult IncludeSummaries::content(const fs::path& file, const ProjectConfig& config) {
  {
    ForkSafeLock lock(mutex_);
    if (auto it = overlays_.find(file); it != overlays_.end()) return {it->second, "", it->second.size(), false};
  }
  return read_file(file, config.max_file_bytes);
}

void IncludeSummaries::scan(Entry& e, const ReadResult& r) {
  e.includes.clear();
  e.macros.clear();
  e.own.reset();
  if (r.error.empty() && !r.too_large && !find_binary_marker(r.text)) {
    e.lang = lang_from_path(e.file.string()).value_or(Lang::hlsl);
    e.includes = include_paths(r.text);
    learn_macros(r.text, known_macros(*e.lang), e.macros);
  } else {
    e.lang.reset();
    e.own = std::make_shared<FileSummary>();
  }
}

const IncludeSummaries::Entry& IncludeSummaries::scanned(const fs::path& file, const ProjectConfig& config) {
  {
    ForkSafeLock lock(mutex_);
    if (auto it = entries_.find(file); it != entries_.end()) return *it->second;
  }
  // Read outside the lock; a file two workers scan together is kept once.
  auto made = std::make_unique<Entry>();
  made->file = file;
  made->engine = engine_file(file, config);
  scan(*made, content(file, config));
  ForkSafeLock lock(mutex_);
  return *entries_.emplace(file, std::move(made)).first->second;
}

const FileSummary& IncludeSummaries::summarised(const Entry& e, const ProjectConfig& config) {
  {
    ForkSafeLock lock(mutex_);
    if (e.own) return *e.own;
  }
  // Read with the macros it would be linted with (see offer): what its own includes define.
  MacroTable included = macros_of(closure_of(e.file, e.includes, config));
  MacroTable macros = macro_table(*e.lang, &included, config.macros);
  auto summary = std::make_shared<FileSummary>();
  ReadResult r = content(e.file, config);
  if (r.error.empty() && !r.too_large) {
    Source src(e.file.string(), r.text);
    *summary = include_summary(src, parse(src, *e.lang, {&macros, 0, config.max_parse_seconds}), config.world_sources, config.host_rebases,
                               model_context(src, *e.lang, nullptr));
  }
  ForkSafeLock lock(mutex_);
  if (!e.own) e.own = std::move(summary);
  return *e.own;
}

void IncludeSummaries::offer(const fs::path& path, Lang lang, const ProjectConfig& config, FileSummary summary) {
  const Entry& e = scanned(canonical(path), config);
  ForkSafeLock lock(mutex_);
  if (!e.own && e.lang == lang) e.own = std::make_shared<FileSummary>(std::move(summary));
}

std::vector<fs::path> IncludeSummaries::direct_includes(const fs::path& path, const ProjectConfig& config) {
  fs::path self = canonical(path);
  return resolve_all(scanned(self, config).includes, self, config);
}

std::vector<const IncludeSummaries::Entry*> IncludeSummaries::closure(const Entry& e, const ProjectConfig& config,
                                                                      std::set<const Entry*>& active) {
  {
    ForkSafeLock lock(mutex_);
    if (auto it = closures_.find(&e); it != closures_.end()) return it->second;
  }
  if (active.size() > kMaxIncludeDepth || !active.insert(&e).second) return {};  // an include cycle stops here
  std::vector<const Entry*> out;
  std::set<const Entry*> seen{&e};
  for (const fs::path& file : resolve_all(e.includes, e.file, config)) {
    const Entry& inc = scanned(file, config);
    if (seen.insert(&inc).second) out.push_back(&inc);
    for (const Entry* deeper : closure(inc, config, active))
      if (seen.insert(deeper).second) out.push_back(deeper);
  }
  active.erase(&e);
  // Inside a cycle the list is cut where the cycle closes: kept only when complete.
  if (active.empty() || std::none_of(out.begin(), out.end(), [&](const Entry* x) { return active.count(x); })) {
    ForkSafeLock lock(mutex_);
    closures_.emplace(&e, out);
  }
  return out;
}

std::vector<const IncludeSummaries::Entry*> IncludeSummaries::closure_of(const fs::path& self, const std::vector<std::string>& includes,
                                                                         const ProjectConfig& config) {
  std::vector<const Entry*> out;
  std::set<fs::path> seen{self};
  for (const fs::path& file : resolve_all(includes, self, config)) {
    if (!seen.insert(file).second) continue;
    const Entry& inc = scanned(file, config);
    out.push_back(&inc);
    std::set<const Entry*> active;
    for (const Entry* deeper : closure(inc, config, active))
      if (seen.insert(deeper->file).second) out.push_back(deeper);
  }
  return out;
}

FileSummary IncludeSummaries::for_file(const fs::path& path, std::string_view text, const ProjectConfig& config) {
  FileSummary out;
  for (const Entry* inc : closure_of(canonical(path), include_paths(text), config)) out.merge(summarised(*inc, config), inc->engine);
  return out;
}

MacroTable IncludeSummaries::macros_of(const std::vector<const Entry*>& entries) {
  MacroTable out;
  for (const Entry* e : entries) out.insert(e->macros.begin(), e->macros.end());
  return out;
}

MacroTable IncludeSummaries::included_macros(const fs::path& path, std::string_view text, const ProjectConfig& config) {
  return macros_of(closure_of(canonical(path), include_paths(text), config));
}

std::vector<fs::path> IncludeSummaries::included_files(const fs::path& path, std::string_view text, const ProjectConfig& config) {
  std::vector<fs::path> out;
  for (const Entry* inc : closure_of(canonical(path), include_paths(text), config)) out.push_back(inc->file);
  return out;
}

bool IncludeSummaries::set_text(const fs::path& path, std::optional<std::string> text, const ProjectConfig& config) {
  fs::path file = canonical(path);
  Entry* changed = nullptr;
  {
    ForkSafeLock lock(mutex_);
    if (text) overlays_[file] = std::move(*text);
    else overlays_.erase(file);
    if (auto it = entries_.find(file); it != entries_.end()) changed = it->second.get();
  }
  if (!changed) return false;  // nothing read it yet
  // Scanned again in place, so every includer's pointer to it stays valid; what depends on its
  // text (its own summary, and the summary of each file whose includes reach it, read with its
  // macros) is summarised again on demand.
  std::vector<std::string> before = changed->includes;
  scan(*changed, content(file, config));
  if (changed->includes != before) {
    ForkSafeLock lock(mutex_);
    closures_.clear();
  }
  std::vector<Entry*> all;
  {
    ForkSafeLock lock(mutex_);
    for (auto& [f, e] : entries_) all.push_back(e.get());
  }
  for (Entry* e : all) {
    if (e == changed || e->own == nullptr || !e->lang) continue;
    std::vector<const Entry*> reach = closure_of(e->file, e->includes, config);
    if (std::find(reach.begin(), reach.end(), changed) == reach.end()) continue;
    ForkSafeLock lock(mutex_);
    e->own.reset();
  }
  return true;
}

}  // namespace lwc
