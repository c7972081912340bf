#pragma once
#include <iosfwd>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/options.h"
#include "cli/report.h"
#include "project/baseline.h"

namespace lwc {

// `lwcport ARGS...`: returns the exit code (0 clean, 1 findings at or above --fail-on, 2 usage
// or fatal error). Output goes to out, errors to err.
int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

class ConfigFinder;
struct ReportTarget;

// Where each file's settings come from: the nearest .lwcport.json, the one --config names, or
// none (--isolated).
std::unique_ptr<ConfigFinder> config_finder(const Options& o);
// --jobs, or every core.
unsigned job_count(const Options& o);

// What lint and host do with each file's findings once they are known: the baseline
// (--baseline, --write-baseline, --prune-baseline), the report in its format and place, the exit code.
class LintOutput {
 public:
  LintOutput(const Options& o, std::ostream& out, std::ostream& err);
  ~LintOutput();
  // Opens the report's target; false (after an error message) when --output cannot be written.
  bool open(ConfigFinder& configs);
  void file(FileReport& report);
  // Ends the report (before the caller's own errors about the run are printed).
  void close();
  // What the run says besides the report, and its exit code (0 or 1); throws when a baseline
  // cannot be written.
  int finish();

 private:
  const Options& o_;
  std::ostream& out_;
  std::ostream& err_;
  std::optional<Baseline> baseline_, recording_;
  std::unique_ptr<ReportTarget> target_;
  std::ostringstream discarded_;
  std::unique_ptr<ReportWriter> writer_;
  std::set<std::string> seen_;  // the files looked at, as the baseline names them
  std::vector<Baseline::Entry> recorded_;
  size_t hidden_ = 0, suppressions_ = 0, suppressed_files_ = 0;
};

// `lwcport host`, set by the lwcport-host program (tool/host_main.cpp); without it, `lwcport host`
// runs that program from beside this one.
using HostCommand = int (*)(const Options&, std::ostream&, std::ostream&);
extern HostCommand host_command;

}  // namespace lwc
