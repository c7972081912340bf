#pragma once
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace lwc {

// A finding's identity across edits (docs/baseline.md): its rule, the text of its span with
// blanks collapsed, and which occurrence of that rule and text it is in its file; never a line
// number, so moving code or editing elsewhere keeps it.
struct Fingerprinted {
  std::string rule;
  std::string text;     // normalised span text
  int occurrence = 0;   // 0 for the first of its rule and text in the file
  std::string fingerprint;  // 16 hex digits of a hash of the three
};

// The span text as fingerprinted: runs of blanks and line breaks become one space, trimmed.
std::string normalised_text(std::string_view text);
// Fingerprints for one file's findings given as (rule, normalised text) in source order.
std::vector<Fingerprinted> fingerprint_all(const std::vector<std::pair<std::string, std::string>>& findings);

// GitHub code scanning's `primaryLocationLineHash` of each line of a text (1-based; the entry at
// index i is line i + 1's, "hash:count"): a rolling hash over the next 100 characters that are not
// blanks, line endings normalised, as the CodeQL action computes it for uploaded SARIF.
std::vector<std::string> line_hashes(std::string_view text);

// A baseline file: findings accepted as they are, so only new ones fail a run.
class Baseline {
 public:
  struct Entry {
    std::string path;  // relative to the baseline's folder, '/'-separated
    Fingerprinted finding;
  };
  // Reads a baseline; throws std::runtime_error naming the file and the problem.
  static Baseline read(const std::filesystem::path& file);
  // An empty baseline that will be written to `file` (for its keys).
  static Baseline at(const std::filesystem::path& file);
  // Writes entries (sorted, so the file diffs well); "" on success, else why not.
  static std::string write(const std::filesystem::path& file, std::vector<Entry> entries);

  // A file's path as the baseline names it.
  std::string key(const std::filesystem::path& file) const;
  // True when the baseline holds this finding of the file (each entry matches once).
  bool take(const std::string& path, const std::string& fingerprint);
  // Entries no finding matched, of the files this run looked at (`seen`) or of files that are gone.
  std::vector<Entry> stale(const std::set<std::string>& seen) const;
  // The other entries: what --prune-baseline writes back.
  std::vector<Entry> pruned(const std::set<std::string>& seen) const;

 private:
  bool is_stale(size_t i, const std::set<std::string>& seen) const;
  std::filesystem::path file_, dir_;
  std::vector<Entry> entries_;
  std::vector<bool> used_;
  std::map<std::pair<std::string, std::string>, std::vector<size_t>> by_key_;  // (path, fingerprint) -> entries
};

}  // namespace lwc
