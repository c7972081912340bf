#pragma once
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/finding.h"
#include "core/unit_counts.h"

namespace lwc {

// What `lwcport host` analyses: C++ translation units, compiled as the project compiles them.
struct HostOptions {
  std::vector<std::string> paths;       // source files, or folders (their sources, from the database when there is one)
  std::string build_dir;                // -p: the folder holding compile_commands.json
  std::vector<std::string> clang_args;  // after `--`: the compile flags when there is no database
  std::set<std::string> select, ignore;  // as lint's
  nlohmann::json tables = nlohmann::json::object();  // .lwcport.json "host": additions to rules/host-world.json
  unsigned jobs = 1;
  // Each unit in a process of its own, so that a crash costs that unit only; off, every unit runs
  // in this process (the fuzz target, where a crash must stop it for the sanitizers to see).
  bool isolate = true;
  // An isolated unit that runs longer is stopped and reported (a unit parses in seconds; only a bug loops).
  unsigned unit_cpu_seconds = 600;
  bool enabled(const std::string& rule) const;
};

// One file with findings or comments: a translation unit's main file, or a project header it includes.
struct HostFile {
  std::string path;     // as the user would name it: relative to the working directory when inside it
  std::string text;     // its bytes, as Clang read them
  std::vector<Finding> findings;
  std::vector<Span> comments;  // for the lwcport-ignore comments
};

struct HostResult {
  std::vector<HostFile> files;  // sorted by path
  size_t units = 0;             // translation units run
  UnitCounts counts;
  std::vector<std::string> skipped;  // the skipped units, as the user would name them
  std::set<std::string> notes;  // what the run changed in units' commands, and why
  std::vector<std::string> errors;  // what stopped the run from starting (no database, no sources)
};

// Parses each translation unit with Clang and runs the host rules' checks; findings in system
// headers are never reported, and one in a header is reported once however many units include it.
HostResult analyze_host(const HostOptions& options);

}  // namespace lwc
