// `lwcport host`: the host engine's findings through lint's outputs (formats, baseline,
// suppressions, exit code), and --fix / --diff through fix's.
#include <fmt/format.h>

#include <set>

#include "cli/commands.h"
#include "fix/apply.h"
#include "fix/diff.h"
#include "host/host.h"
#include "project/config.h"
#include "project/files.h"
#include "rules/analyze.h"
#include "rules/rule.h"

namespace lwc {

namespace {

HostResult analyze(const Options& o, const ProjectConfig& config) {
  HostOptions h;
  h.paths = o.paths;
  h.build_dir = o.build_dir;
  h.clang_args = o.clang_args;
  h.select = o.select.empty() ? std::set<std::string>(config.select.begin(), config.select.end()) : o.select;
  h.ignore = o.ignore;
  h.ignore.insert(config.ignore.begin(), config.ignore.end());
  h.tables = config.host;
  h.jobs = job_count(o);
  HostResult result = analyze_host(h);
  for (HostFile& file : result.files) {
    Source source(file.path, file.text);
    apply_suppressions(source, file.comments, [&](const RuleInfo& r) { return r.host || r.id == kUnusedSuppressionRule ? h.enabled(r.id) : false; },
                       file.findings);
    for (Finding& f : file.findings)
      if (auto it = config.severity.find(f.rule); it != config.severity.end()) f.severity = it->second;
  }
  return result;
}

// --fix and --diff: each file's chosen fixes applied once (--diff prints them instead).
struct Applied {
  int fixed = 0, failed = 0;
  std::set<std::string> files;  // written
};

Applied apply(const Options& o, const HostResult& result, std::ostream& out, std::ostream& err) {
  Applied done;
  for (const HostFile& file : result.files) {
    Source source(file.path, file.text);
    std::vector<Edit> edits;
    std::vector<const Fix*> chosen = choose_fixes(file.findings, o.unsafe_fixes);
    for (const Fix* fix : chosen) edits.insert(edits.end(), fix->edits.begin(), fix->edits.end());
    if (edits.empty()) continue;
    std::string text = apply_edits(source, edits);
    if (o.diff) {
      out << unified_diff(file.path, file.text, text);
      continue;
    }
    if (std::string why = replace_file(file.path, file.text, text); !why.empty()) {
      err << fmt::format("lwcport: error: {}: {}\n", file.path, why);
      ++done.failed;
      continue;
    }
    done.fixed += static_cast<int>(chosen.size());
    done.files.insert(file.path);
  }
  return done;
}

}  // namespace

int run_host(const Options& o, std::ostream& out, std::ostream& err) {
  std::unique_ptr<ConfigFinder> configs = config_finder(o);
  const ProjectConfig& config = *configs->for_dir(".");
  HostResult result = analyze(o, config);
  for (const std::string& e : result.errors) err << "lwcport: error: " << e << '\n';
  if (!result.errors.empty() && result.units == 0) return 2;
  if (o.diff) {
    apply(o, result, out, err);
    bool any = false;
    for (const HostFile& f : result.files) any = any || !choose_fixes(f.findings, o.unsafe_fixes).empty();
    return any && o.fail_on ? 1 : 0;
  }
  if (o.fix_in_place) {
    // Fixes that clash (two that declare the same new member) wait for the next round, which
    // re-analyses what the last one wrote; a few rounds settle any file.
    std::set<std::string> files;
    int fixed = 0;
    for (int round = 0; round < 4; ++round) {
      Applied done = apply(o, result, out, err);
      if (done.failed) return 2;
      if (done.fixed == 0) break;
      fixed += done.fixed;
      files.insert(done.files.begin(), done.files.end());
      result = analyze(o, config);  // what remains, from the fixed files
    }
    err << fmt::format("Fixed {} finding(s) in {} file(s).\n", fixed, files.size());
  }
  LintOutput output(o, out, err);
  if (!output.open(*configs)) return 2;
  for (const HostFile& file : result.files) {
    Source source(file.path, file.text);
    FileReport report{file.path, {}};
    for (const Finding& f : file.findings) report.findings.push_back(locate(source, f));
    add_fingerprints(report, source, o.report.format == Format::sarif);
    output.file(report);
  }
  output.close();
  int code = output.finish();
  return result.errors.empty() ? code : 2;
}

}  // namespace lwc
