#include "cli/includes.h"

#include "cli/files.h"
#include "rules/analyze.h"

namespace fs = std::filesystem;

namespace lwc {

namespace {
constexpr int kMaxIncludeDepth = 16;

}  // namespace

std::optional<fs::path> IncludeSummaries::resolve(const std::string& include, const fs::path& from,
                                                  const ProjectConfig& config) const {
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

std::shared_ptr<const FileSummary> IncludeSummaries::own_summary(const fs::path& file, const ProjectConfig& config,
                                                                std::string& text) {
  std::error_code ec;
  fs::path key = fs::weakly_canonical(file, ec);
  {
    std::lock_guard lock(mutex_);
    if (auto it = cache_.find(key); it != cache_.end()) {
      text = it->second.second;
      return it->second.first;
    }
  }
  auto summary = std::make_shared<FileSummary>();
  ReadResult r = read_file(file, config.max_file_bytes);
  std::optional<Lang> lang = lang_from_path(file.string());
  if (r.error.empty() && !r.too_large && !find_binary_marker(r.text)) {
    Source src(file.string(), r.text);
    SyntaxTree tree = parse(src, lang.value_or(Lang::hlsl));
    std::optional<UnrealEra> era;
    if (tree.lang == Lang::hlsl && is_unreal_source(src.path(), r.text)) era = infer_unreal_era(r.text);
    WorldModel model(tree, world_data(tree.lang, config.world_sources), {nullptr, names_as_evidence(src, tree.lang), !era, era});
    *summary = model.summary();
    learn_macros(r.text, known_macros(tree.lang), summary->macros);
    text = r.text;
  }
  std::lock_guard lock(mutex_);
  cache_.emplace(key, std::make_pair(summary, text));
  return summary;
}

void IncludeSummaries::merge_includes(const fs::path& path, std::string_view text, const ProjectConfig& config,
                                      FileSummary& into, std::set<fs::path>& seen, int depth) {
  if (depth > kMaxIncludeDepth) return;
  for (const std::string& inc : include_paths(text)) {
    auto file = resolve(inc, path, config);
    if (!file || !seen.insert(fs::weakly_canonical(*file)).second) continue;
    std::string included_text;
    auto summary = own_summary(*file, config, included_text);
    into.merge(*summary);
    merge_includes(*file, included_text, config, into, seen, depth + 1);
  }
}

FileSummary IncludeSummaries::for_file(const fs::path& path, std::string_view text, const ProjectConfig& config) {
  FileSummary out;
  std::set<fs::path> seen{fs::weakly_canonical(path)};
  merge_includes(path, text, config, out, seen, 0);
  return out;
}

}  // namespace lwc
