// `lwcport host`: the host engine's findings through lint's outputs (formats, baseline,
// suppressions, exit code), and --fix / --diff through fix's.
#include <fmt/format.h>

#include <map>
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

// --fix and --diff: the chosen fixes applied once (--diff prints them instead).
struct Applied {
  int fixed = 0, failed = 0;
  std::set<std::string> files;  // written
};

// Every finding of the run, each fix's edits naming their file: a fix may edit two files (a
// member declared in a header), and two units' fixes may clash there, so fixes are chosen over
// the whole run, not file by file.
std::vector<Finding> with_edit_paths(const HostResult& result) {
  std::vector<Finding> all;
  for (const HostFile& file : result.files)
    for (Finding f : file.findings) {
      for (Fix& fix : f.fixes)
        for (Edit& e : fix.edits)
          if (e.path.empty()) e.path = file.path;
      all.push_back(std::move(f));
    }
  return all;
}

Applied apply(const Options& o, const HostResult& result, std::ostream& out, std::ostream& err) {
  Applied done;
  std::vector<Finding> all = with_edit_paths(result);
  std::vector<const Fix*> chosen = choose_fixes(all, o.unsafe_fixes);
  for (const HostFile& file : result.files) {
    std::vector<Edit> edits;
    int fixes = 0;  // counted in the file of the finding: its first edit's
    for (const Fix* fix : chosen) {
      for (const Edit& e : fix->edits)
        if (e.path == file.path) edits.push_back(e);
      fixes += fix->edits.front().path == file.path;
    }
    if (edits.empty()) continue;
    std::string text = apply_edits(Source(file.path, file.text), edits);
    if (o.diff) {
      out << unified_diff(file.path, file.text, text);
      continue;
    }
    if (std::string why = replace_file(file.path, file.text, text); !why.empty()) {
      err << fmt::format("lwcport: error: {}: {}\n", file.path, why);
      ++done.failed;
      continue;
    }
    done.fixed += fixes;
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
    bool any = !choose_fixes(with_edit_paths(result), o.unsafe_fixes).empty();
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
  for (const std::string& note : result.notes) err << "lwcport: note: " << note << '\n';
  if (!result.skipped.empty())
    err << fmt::format("lwcport: note: {} unit(s) of the compilation database are not on disk (sources the build generates?) and were "
                       "skipped, first {}\n", result.skipped.size(), result.skipped.front());
  Options with_units = o;
  with_units.report.units = result.counts;
  LintOutput output(with_units, out, err);
  if (!output.open(*configs)) return 2;
  std::map<std::string, Source> sources;  // every file, for the edits a fix makes in another one
  for (const HostFile& file : result.files) sources.emplace(file.path, Source(file.path, file.text));
  auto other = [&](const std::string& path) -> const Source* {
    auto it = sources.find(path);
    return it == sources.end() ? nullptr : &it->second;
  };
  for (const HostFile& file : result.files) {
    const Source& source = sources.at(file.path);
    FileReport report{file.path, {}};
    for (const Finding& f : file.findings) report.findings.push_back(locate(source, f, other));
    add_fingerprints(report, source, o.report.format == Format::sarif);
    output.file(report);
  }
  output.close();
  int code = output.finish();
  return result.errors.empty() ? code : 2;
}

}  // namespace lwc
