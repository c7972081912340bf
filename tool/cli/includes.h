#pragma once
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "cli/config.h"
#include "world/model.h"

namespace lwc {

// Resolves #include paths (next to the including file, then include dirs, then virtual roots
// such as /Engine/) and learns what the included files declare. Missing includes are skipped:
// lwcport never needs them to lint, they only add context. Thread-safe; each file is read once.
class IncludeSummaries {
 public:
  // Where `#include "include"` in `from` leads: virtual roots, the including folder, include dirs.
  std::optional<std::filesystem::path> resolve(const std::string& include, const std::filesystem::path& from,
                                               const ProjectConfig& config) const;
  // What everything `text` (the file at `path`) includes declares, transitively.
  FileSummary for_file(const std::filesystem::path& path, std::string_view text, const ProjectConfig& config);

 private:
  void merge_includes(const std::filesystem::path& path, std::string_view text, const ProjectConfig& config,
                      FileSummary& into, std::set<std::filesystem::path>& seen, int depth);
  std::shared_ptr<const FileSummary> own_summary(const std::filesystem::path& file, const ProjectConfig& config,
                                                 std::string& text);

  std::mutex mutex_;
  std::map<std::filesystem::path, std::pair<std::shared_ptr<const FileSummary>, std::string>> cache_;
};

}  // namespace lwc
