#pragma once
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "project/config.h"
#include "project/files.h"
#include "world/model.h"

namespace lwc {

// Resolves #include paths (next to the including file, then include dirs, then virtual roots
// such as /Engine/) and learns what the included files declare. Missing includes are skipped:
// lwcport never needs them to lint, they only add context. Thread-safe; each file is read and
// parsed once per run, each include resolved once per folder, and each file's transitive
// include list worked out once.
// One of Unreal's own shaders: under the folder a project maps `/Engine/` to, or in a `Shaders`
// folder laid out as the engine's (under `Engine/`, or holding `Private/Common.ush`; a plugin's
// are in `Plugins/<name>/Shaders` and hold no Common.ush of their own).
bool engine_file(const std::filesystem::path& file, const ProjectConfig& config);

class IncludeSummaries {
 public:
  // Where `#include "include"` in `from` leads: virtual roots, the including folder, include dirs.
  std::optional<std::filesystem::path> resolve(const std::string& include, const std::filesystem::path& from,
                                               const ProjectConfig& config);
  // What everything `text` (the file at `path`) includes declares, transitively: the first
  // declaration in include order wins.
  FileSummary for_file(const std::filesystem::path& path, std::string_view text, const ProjectConfig& config);
  // What everything `text` (the file at `path`) includes teaches about macros, transitively (the
  // first definition in include order wins): the macros of for_file's summary, read from the
  // includes' #define lines alone, so that parsing the file as lint does parses none of them.
  MacroTable included_macros(const std::filesystem::path& path, std::string_view text, const ProjectConfig& config);
  // The files `path` includes directly (canonical, in order): for scheduling includes first.
  std::vector<std::filesystem::path> direct_includes(const std::filesystem::path& path, const ProjectConfig& config);
  // A lint target's own parse gives its summary (include_summary), so a file that is both a
  // target and an include is parsed once. Both ways read it with the same macros, so the
  // summary does not depend on which came first.
  void offer(const std::filesystem::path& path, Lang lang, const ProjectConfig& config, FileSummary summary);
  // The files everything `text` (the file at `path`) includes lead to, transitively (canonical).
  std::vector<std::filesystem::path> included_files(const std::filesystem::path& path, std::string_view text,
                                                    const ProjectConfig& config);
  // The text an editor holds for a file (none: the file on disk again). Whatever was learnt
  // from the file, and from every file whose includes reach it, is learnt again on demand; true
  // when something had been learnt from it.
  bool set_text(const std::filesystem::path& path, std::optional<std::string> text, const ProjectConfig& config);
  // The path with links and dots resolved (cached: lint asks for each file many times).
  std::filesystem::path canonical(const std::filesystem::path& p);

 private:
  // A file as its includers see it: first scanned (its #include lines and #defines, no parse),
  // then summarised on demand.
  struct Entry {
    std::filesystem::path file;  // canonical
    std::optional<Lang> lang;    // none: not readable as a shader
    std::vector<std::string> includes;  // as written
    MacroTable macros;                  // what its #defines teach
    bool engine = false;  // one of the engine's own shaders (its functions keep the engine's contracts)
    mutable std::shared_ptr<const FileSummary> own;  // null until summarised; set once, under the mutex
  };
  // A file's text: the editor's when it holds the file, else the disk's.
  ReadResult content(const std::filesystem::path& file, const ProjectConfig& config);
  // Reads a file's #include lines and #defines into `e` (and forgets its summary).
  static void scan(Entry& e, const ReadResult& r);
  const Entry& scanned(const std::filesystem::path& canonical, const ProjectConfig& config);
  const FileSummary& summarised(const Entry& e, const ProjectConfig& config);
  // What `entries` teach about macros, the first definition winning.
  static MacroTable macros_of(const std::vector<const Entry*>& entries);
  // Everything `e` includes, transitively, in include order (`active`: the includes being
  // expanded above it, to stop at a cycle).
  std::vector<const Entry*> closure(const Entry& e, const ProjectConfig& config, std::set<const Entry*>& active);
  // Everything the file at `self` (including `includes`) includes, transitively, in include order.
  std::vector<const Entry*> closure_of(const std::filesystem::path& self, const std::vector<std::string>& includes,
                                       const ProjectConfig& config);
  // The canonical files `includes` (written in the file at `from`) lead to, in order.
  std::vector<std::filesystem::path> resolve_all(const std::vector<std::string>& includes, const std::filesystem::path& from,
                                                 const ProjectConfig& config);

  std::mutex mutex_;  // taken with ForkSafeLock: a compile child resolves includes through it
  std::map<std::filesystem::path, std::unique_ptr<Entry>> entries_;
  std::map<const Entry*, std::vector<const Entry*>> closures_;
  std::map<std::tuple<const ProjectConfig*, std::filesystem::path, std::string>, std::optional<std::filesystem::path>> resolved_;
  std::map<std::filesystem::path, std::filesystem::path> canonical_;
  std::map<std::filesystem::path, std::string> overlays_;  // canonical file -> the editor's text
};

}  // namespace lwc
