#pragma once
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cli/report.h"
#include "fix/scene.h"
#include "lang/syntax.h"

namespace lwc {

// A mistake on the command line: one line naming it, and the command whose help explains.
struct UsageError : std::runtime_error {
  UsageError(const std::string& what, std::string command = "") : std::runtime_error(what), command(std::move(command)) {}
  std::string command;
};

struct Options {
  std::string command;  // lint, fix, verify, parse, host, rules, rule, report, lsp, help, version
  std::string help_for;  // help: the command asked about ("" for the overview)
  std::vector<std::string> paths;  // "-" is standard input
  ReportOptions report;
  std::string color = "auto";
  std::optional<Severity> fail_on = Severity::warning;
  std::set<std::string> select, ignore;
  std::optional<Lang> lang;
  unsigned jobs = 0;
  std::string output;
  std::optional<Scene> scene;
  Strategy strategy = Strategy::automatic;
  bool diff = false, unsafe_fixes = false;
  bool shaderlib = false;
  bool verify = false;  // fix: apply only the rewrites that pass on the device
  bool verbose = false;  // parse: list each syntax error with the text around it
  bool check_build = false;  // fix: a file whose fix would break its build is held back
  bool force = false;  // fix: replace files with other hard links too (splitting them)
  double timeout_seconds = 60;  // per kernel on the device
  std::string log_file;  // lsp: where the server logs
  std::string stdin_filename;  // `-`: the name standing for standard input (language, config, suppressions)
  std::string config_file;  // every file uses this .lwcport.json instead of the nearest one
  bool isolated = false;  // no .lwcport.json at all: the built-in defaults
  std::string baseline_file;        // lint: report only findings not in it
  std::string write_baseline_file;  // lint: record the current findings there
  bool prune_baseline = false;      // lint --baseline: drop the entries that no longer match
  bool add_suppressions = false;    // lint: a suppression comment for each finding, written into the files
  std::string out_dir = "lwcport-report";  // report: where report.html, .md and .json go
  int history = 0;                  // report: the counts at each of the last N commits
  std::string since;                // report: ... or at each commit after REV
  std::string build_dir;            // host -p: the folder holding compile_commands.json
  std::vector<std::string> clang_args;  // host: after `--`, the compile flags when there is no database
  bool fix_in_place = false;        // host --fix: apply the fixes (the safe ones; --unsafe-fixes for the rest)
  std::vector<std::string> host_paths;  // report --host: the C++ host code to analyse too
};

// Reads the command line; throws UsageError for anything it does not accept.
Options parse_options(const std::vector<std::string>& args);
// `lwcport: error: WHAT (see `lwcport CMD --help`)`, one line.
std::string usage_error_line(const UsageError& e);
// The help text of a command, or the overview for "".
std::string usage(std::string_view command);

}  // namespace lwc
