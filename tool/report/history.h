#pragma once
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace lwc {

// One commit of a tree's history and the files it holds under the report's paths.
struct CommitFiles {
  std::string commit, date, subject;
  std::vector<std::pair<std::string, std::string>> files;  // (path relative to the repository's top, blob id)
};

// The repository around `dir`: its top folder. Throws std::runtime_error when git or the
// repository is missing.
std::filesystem::path git_top(const std::filesystem::path& dir);
// The last `count` commits of HEAD's first-parent history (or those after `since`, when given),
// oldest first, each with the blobs under `paths` (relative to the top). Throws on git's errors.
std::vector<CommitFiles> git_history(const std::filesystem::path& top, const std::vector<std::string>& paths, int count,
                                     const std::string& since);
// The contents of these blobs, read in one `git cat-file --batch`.
std::map<std::string, std::string> git_blobs(const std::filesystem::path& top, const std::set<std::string>& ids);

}  // namespace lwc
