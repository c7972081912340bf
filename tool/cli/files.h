#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/config.h"
#include "lang/syntax.h"

namespace lwc {

// A file to lint, or a path that could not be walked (error set).
struct InputFile {
  std::filesystem::path path;
  std::string display;  // as the user would write it: relative to the argument given
  std::shared_ptr<const ProjectConfig> config;
  std::string error;
};

// Expands the command-line paths: folders recurse (sorted, following symlinks but never into a
// folder already being walked), shader extensions only, config excludes applied. Files named
// explicitly are always linted. The result is sorted by display path.
std::vector<InputFile> discover(const std::vector<std::string>& args, ConfigFinder& configs);

struct ReadResult {
  std::string text;
  std::string error;          // set when the file could not be read
  size_t size = 0;
  bool too_large = false;     // larger than the limit: not read
};
ReadResult read_file(const std::filesystem::path& path, size_t max_bytes);

}  // namespace lwc
