#include "cli/commands.h"

#include <pthread.h>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "project/baseline.h"
#include "report/history.h"
#include "report/migration.h"
#include "core/embedded.h"
#include "project/config.h"
#include "project/files.h"
#include "project/includes.h"
#include "cli/options.h"
#include "cli/report.h"
#include "cli/verify_report.h"
#include "lsp/server.h"
#include "fix/apply.h"
#include "fix/diff.h"
#include "fix/suppress.h"
#include "fix/scene.h"
#include "rules/analyze.h"
#include "rules/rule.h"
#include "lang/lexer.h"
#include "lang/tokens.h"
#include "shaderlib/shaderlib.h"
#include "verify/build_environment.h"
#include "verify/harness.h"
#include "verify/kernel_builder.h"
#include "verify/library_accuracy.h"
#include "verify/probes.h"
#include "verify/worker.h"

namespace fs = std::filesystem;

namespace lwc {

namespace {

// Runs `work(i)` for every index on `jobs` threads; results land in per-index slots, so output
// order never depends on scheduling.
template <typename Work>
void parallel_for(size_t count, unsigned jobs, Work work) {
  std::atomic<size_t> next{0};
  auto worker = [&]() {
    for (size_t i; (i = next.fetch_add(1)) < count;) work(i);
  };
  std::vector<std::thread> threads;
  unsigned n = std::max(1u, std::min<unsigned>(jobs, static_cast<unsigned>(count)));
  for (unsigned t = 1; t < n; ++t) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
}

// Runs `work(i)` for every index on `jobs` threads (in `order` when given) and hands each result
// to `emit` on this thread, in index order, as soon as it is ready; a result is freed once
// emitted, so memory holds only the files in flight and those done ahead of their turn.
template <typename Result, typename Work, typename Emit>
void run_in_order(size_t count, unsigned jobs, Work work, Emit emit, const std::vector<size_t>* order = nullptr) {
  std::vector<std::optional<Result>> slots(count);
  std::mutex mutex;
  std::condition_variable ready;
  std::atomic<size_t> next{0};
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < std::min<size_t>(jobs, count); ++t) {
    workers.emplace_back([&]() {
      block_interrupts_in_this_thread();
      for (size_t k; (k = next.fetch_add(1)) < count;) {
        size_t i = order ? (*order)[k] : k;
        Result r = work(i);
        std::lock_guard lock(mutex);
        slots[i] = std::move(r);
        ready.notify_all();
      }
    });
  }
  for (size_t i = 0; i < count; ++i) {
    std::unique_lock lock(mutex);
    ready.wait(lock, [&] { return slots[i].has_value(); });
    Result r = std::move(*slots[i]);
    slots[i].reset();
    lock.unlock();
    emit(r);
  }
  for (auto& w : workers) w.join();
}

}  // namespace
unsigned job_count(const Options& o) { return o.jobs ? o.jobs : std::max(1u, std::thread::hardware_concurrency()); }
namespace {

// A file read and ready to analyse, or the report of why it is not.
struct LoadedFile {
  std::optional<Source> source;
  AnalyzeOptions options;
  std::unique_ptr<FileSummary> includes;  // options.includes points here: kept at a stable address
  std::optional<FileReport> problem;
};

LoadedFile load(const InputFile& file, const Options& o, IncludeSummaries& includes) {
  LoadedFile out;
  const ProjectConfig& config = *file.config;
  auto problem = [&](Finding f) {
    Source empty(file.display, "");
    out.problem = FileReport{file.display, {locate(empty, f)}};
    return std::move(out);
  };
  if (!file.error.empty())
    return problem(input_finding(Severity::error, 0, "cannot read: " + file.error, "check the path and its permissions"));
  if (const auto& u = file.unmapped)
    return problem(input_finding(
        Severity::note, 0,
        fmt::format("this file reads as {} ({}), but `{}` is not an extension lwcport maps: it{} {} not linted", u->language, u->words,
                    u->extension, u->more ? fmt::format(" and {} more `{}` file{}", u->more, u->extension, u->more == 1 ? "" : "s") : "",
                    u->more ? "are" : "is"),
        fmt::format("to lint them, add \"extensions\": {{\"{0}\": \"{1}\"}} to .lwcport.json; \"{0}\": \"none\" says they are not shaders",
                    u->extension, u->language == "HLSL" ? "hlsl" : "glsl")));
  ReadResult r = file.content ? ReadResult{*file.content, "", file.content->size(), file.content->size() > config.max_file_bytes}
                              : read_file(file.path, config.max_file_bytes);
  if (!r.error.empty())
    return problem(input_finding(Severity::error, 0, "cannot read: " + unreadable_because(file.path, r.error), "check the path and its permissions"));
  if (r.too_large) return problem(too_large_finding(r.size, config.max_file_bytes));
  AnalyzeOptions& a = out.options;
  a = analysis_options(config);
  a.lang = o.lang;
  if (!o.select.empty()) a.select = o.select;  // the command line's selection replaces the project's
  a.ignore.insert(o.ignore.begin(), o.ignore.end());
  a.strategy = o.strategy;
  if (o.scene) a.scene = o.scene->for_path(file.display);
  out.source.emplace(file.display, std::move(r.text));
  a.engine_file = engine_file(includes.canonical(file.path), config);
  if (out.source->text().find("include") != std::string::npos) {
    out.includes = std::make_unique<FileSummary>(includes.for_file(file.path, out.source->text(), config));
    a.includes = out.includes.get();
  }
  return out;
}

// A failure inside one file's work (an exception from any stage) is that file's error; the run
// goes on with the other files.
FileReport failed_file(const InputFile& file, const std::exception& e) {
  Source empty(file.display, "");
  return FileReport{file.display,
                    {locate(empty, input_finding(Severity::error, 0, std::string("internal error: ") + e.what(),
                                                 "the other files were analysed; please report this with the file"))}};
}

// --add-suppressions: the lines of a file's findings, each with the rules to silence there.
SuppressionSites suppression_sites(const Source& source, const AnalyzeOptions& options, const std::vector<Finding>& findings) {
  std::optional<FileFormat> format = format_for(source, options);
  bool script = format && format->container == Container::javascript;
  const std::string& text = source.text();
  SuppressionSites sites;
  for (const Finding& f : findings) {
    if (f.rule == kInputRule || f.rule == kUnusedSuppressionRule) continue;  // not code to silence
    int line = source.position(f.span.begin).line;
    sites.rules_by_line[line].insert(f.rule);
    if (!script) continue;
    // In a script the line may end outside the GLSL literal: the comment goes right after the
    // finding (or its first word, when it spans lines), still inside.
    size_t at = f.span.end;
    if (source.position(f.span.end).line != line) {
      at = f.span.begin;
      while (at < text.size() && (std::isalnum(static_cast<unsigned char>(text[at])) || text[at] == '_')) ++at;
    }
    auto [it, fresh] = sites.inside_at.emplace(line, at);
    if (!fresh) it->second = std::min(it->second, at);
  }
  return sites;
}

// `included`: another target includes it, so its summary is wanted.
FileReport lint_file(const InputFile& file, const Options& o, IncludeSummaries& includes, bool included) {
  LoadedFile f = load(file, o, includes);
  if (f.problem) return std::move(*f.problem);
  FileReport report{file.display, {}};
  report.has_code = holds_shader_code(*f.source, f.options);
  report.era = file_era(*f.source, f.options);
  std::optional<FileSummary> own;
  if (included) f.options.summary_for_includers = &own;
  std::vector<Finding> findings = analyze(*f.source, f.options);
  if (o.add_suppressions) {
    // The comments are written, then the new text analysed again: what it still reports is the report.
    SuppressionSites sites = suppression_sites(*f.source, f.options, findings);
    std::string text = with_suppressions(f.source->text(), sites);
    if (text != f.source->text()) {
      std::string why = replace_file(file.path, f.source->text(), text, o.force);
      if (!why.empty()) {
        report.findings.push_back(locate(*f.source, input_finding(Severity::error, 0, "cannot write the suppressions: " + why,
                                                                  "the other files were still written")));
      } else {
        report.added_suppressions = static_cast<int>(sites.rules_by_line.size());
        f.source.emplace(file.display, std::move(text));
        findings = analyze(*f.source, f.options);
      }
    }
  }
  for (const Finding& finding : findings) report.findings.push_back(locate(*f.source, finding));
  add_fingerprints(report, *f.source, o.report.format == Format::sarif);
  if (auto lang = language_for(*f.source, f.options); own && lang) includes.offer(file.path, *lang, *file.config, std::move(*own));
  return report;
}

// The order to lint in: each file after the files it includes that are lint targets too, so
// their summaries come from their own parse (IncludeSummaries::offer). Reports still come out in
// path order.
struct LintOrder {
  std::vector<size_t> order;
  std::vector<bool> included;  // per file: another target includes it
};
LintOrder includes_first(const std::vector<InputFile>& files, IncludeSummaries& includes) {
  std::map<fs::path, size_t> index;
  for (size_t i = 0; i < files.size(); ++i)
    if (files[i].error.empty()) index.emplace(includes.canonical(files[i].path), i);
  std::vector<std::vector<size_t>> deps(files.size());
  LintOrder out{{}, std::vector<bool>(files.size(), false)};
  for (const auto& [path, i] : index)
    for (const fs::path& inc : includes.direct_includes(path, *files[i].config))
      if (auto it = index.find(inc); it != index.end()) {
        deps[i].push_back(it->second);
        out.included[it->second] = true;
      }
  std::vector<size_t>& order = out.order;
  std::vector<char> seen(files.size(), 0);
  for (size_t root = 0; root < files.size(); ++root) {
    if (seen[root]) continue;
    seen[root] = 1;
    std::vector<std::pair<size_t, size_t>> stack{{root, 0}};  // file, next dependency
    while (!stack.empty()) {
      auto [file, next] = stack.back();
      if (next < deps[file].size()) {
        ++stack.back().second;
        size_t dep = deps[file][next];
        if (!seen[dep]) {
          seen[dep] = 1;
          stack.push_back({dep, 0});
        }
        continue;
      }
      order.push_back(file);
      stack.pop_back();
    }
  }
  return out;
}

}  // namespace

std::unique_ptr<ConfigFinder> config_finder(const Options& o) {
  if (o.isolated) return std::make_unique<ConfigFinder>(std::make_shared<const ProjectConfig>());
  if (!o.config_file.empty()) return std::make_unique<ConfigFinder>(ConfigFinder::read(o.config_file));
  return std::make_unique<ConfigFinder>();
}
namespace {

// Colour under --color auto: FORCE_COLOR or CLICOLOR_FORCE (set, not "0") force it, NO_COLOR
// turns it off, else a terminal gets it.
bool colour(const Options& o) {
  if (o.color != "auto") return o.color == "always";
  auto set = [](const char* name) {
    const char* v = std::getenv(name);
    return v && *v && std::string_view(v) != "0";
  };
  if (set("FORCE_COLOR") || set("CLICOLOR_FORCE")) return true;
  const char* no_color = std::getenv("NO_COLOR");
  if (no_color && *no_color) return false;
  return o.output.empty() && ::isatty(STDOUT_FILENO);
}

// The report goes to standard output or --output; false (after an error message) if that file
// cannot be opened.
}  // namespace
struct ReportTarget {
  std::ofstream file;
  std::ostream* stream = nullptr;
};
namespace {
bool open_target(const Options& o, ConfigFinder& configs, std::ostream& out, std::ostream& err, ReportTarget& target, ReportOptions& ro) {
  ro = o.report;
  ro.color = colour(o);
  ro.working_dir = fs::current_path().string();
  ro.help_uri_base = configs.for_dir(".")->help_uri_base;
  target.stream = &out;
  if (o.output.empty()) return true;
  target.file.open(o.output, std::ios::binary);
  if (!target.file) {
    err << fmt::format("lwcport: error: cannot write {}\n", o.output);
    return false;
  }
  target.stream = &target.file;
  return true;
}

// Standard input as a file named by --stdin-filename (its language, config and suppressions), or `-`.
InputFile standard_input(const Options& o, ConfigFinder& configs) {
  if (o.stdin_filename.empty() && !o.lang)
    throw UsageError("reading standard input needs --stdin-filename NAME (or --lang) to know its language", o.command);
  InputFile file;
  file.path = o.stdin_filename.empty() ? fs::path("-") : fs::path(o.stdin_filename);
  file.display = o.stdin_filename.empty() ? "-" : o.stdin_filename;
  fs::path dir = file.path.has_parent_path() ? file.path.parent_path() : fs::path(".");
  file.config = configs.for_dir(dir);
  std::ostringstream text;
  text << std::cin.rdbuf();
  file.content = text.str();
  return file;
}

// The files to work on; each config's warnings are printed once, naming the config.
std::vector<InputFile> input_files(const Options& o, ConfigFinder& configs, std::ostream& err) {
  std::vector<InputFile> files;
  if (o.paths.size() == 1 && o.paths[0] == "-") files.push_back(standard_input(o, configs));
  else files = discover(o.paths.empty() ? std::vector<std::string>{"."} : o.paths, configs);
  for (const auto& config : configs.loaded())
    for (const std::string& w : config->warnings) err << fmt::format("lwcport: warning: {}: {}\n", (config->dir / ".lwcport.json").string(), w);
  return files;
}

// Nothing is silent: a path given on the command line that yields no shader code is an error
// (a typo in a CI script must not pass). `with_code` counts, per argument, the files that hold some.
bool every_argument_had_code(const Options& o, const std::vector<size_t>& with_code, std::ostream& err) {
  bool ok = true;
  std::vector<std::string> args = o.paths.empty() ? std::vector<std::string>{"."} : o.paths;
  for (size_t i = 0; i < args.size(); ++i) {
    if (i < with_code.size() && with_code[i] > 0) continue;
    std::error_code ec;
    std::string why = !fs::exists(args[i], ec) ? "no such file or folder"
                      : fs::is_directory(args[i], ec)
                          ? "no shader file in it (extensions: " + FormatTable::defaults().extensions() + "; map others in .lwcport.json \"extensions\")"
                          : "not a shader file lwcport knows (map its extension in .lwcport.json \"extensions\", or pass --lang)";
    err << fmt::format("lwcport: error: {}: {}\n", args[i], why);
    ok = false;
  }
  return ok;
}

// Counts the files of each command-line argument that hold shader code.
struct CodeCounter {
  const std::vector<InputFile>& files;
  std::vector<size_t> with_code;
  size_t next = 0;
  explicit CodeCounter(const std::vector<InputFile>& f) : files(f) {}
  void add(const FileReport& r) {
    const InputFile& file = files[next++];
    bool known = r.findings.empty() || r.findings.front().message.rfind("not a shader file", 0) != 0;
    if (with_code.size() <= file.argument) with_code.resize(file.argument + 1);
    if (r.has_code && known && file.error.empty() && !file.unmapped) ++with_code[file.argument];
  }
};

// What a baseline run says besides the report, on standard error: how many findings it hid, and
// which of its entries no longer match (--prune-baseline drops them).
void finish_baseline(const Options& o, Baseline& baseline, const std::set<std::string>& seen, size_t hidden, std::ostream& err) {
  std::vector<Baseline::Entry> stale = baseline.stale(seen);
  err << fmt::format("lwcport: baseline {}: {} known finding(s) not reported", o.baseline_file, hidden);
  if (stale.empty()) {
    err << ".\n";
    return;
  }
  err << fmt::format("; {} no longer match{} (fixed, or the code changed){}\n", stale.size() == 1 ? "1 entry" : std::to_string(stale.size()) + " entries",
                     stale.size() == 1 ? "es" : "", o.prune_baseline ? ", dropped:" : ":");
  constexpr size_t kShown = 20;
  for (size_t i = 0; i < stale.size() && i < kShown; ++i)
    err << fmt::format("  {}: {}: `{}`\n", stale[i].path, stale[i].finding.rule, stale[i].finding.text.substr(0, 80));
  if (stale.size() > kShown) err << fmt::format("  ... and {} more\n", stale.size() - kShown);
  if (!o.prune_baseline) {
    err << fmt::format("  (`lwcport lint --baseline {} --prune-baseline` drops them)\n", o.baseline_file);
    return;
  }
  if (std::string why = Baseline::write(o.baseline_file, baseline.pruned(seen)); !why.empty())
    throw std::runtime_error(fmt::format("{}: cannot write the baseline: {}", o.baseline_file, why));
}

}  // namespace

LintOutput::LintOutput(const Options& o, std::ostream& out, std::ostream& err) : o_(o), out_(out), err_(err) {
  if (!o.baseline_file.empty()) baseline_ = Baseline::read(o.baseline_file);
  // --write-baseline: the entries are relative to the file being written, as --baseline reads them.
  if (!o.write_baseline_file.empty()) recording_ = Baseline::at(o.write_baseline_file);
}

LintOutput::~LintOutput() = default;

bool LintOutput::open(ConfigFinder& configs) {
  target_ = std::make_unique<ReportTarget>();
  ReportOptions ro;
  if (!open_target(o_, configs, out_, err_, *target_, ro)) return false;
  writer_ = std::make_unique<ReportWriter>(recording_ ? discarded_ : *target_->stream, ro);  // --write-baseline prints no report
  return true;
}

void LintOutput::file(FileReport& r) {
  suppressions_ += r.added_suppressions;
  suppressed_files_ += r.added_suppressions > 0;
  if (recording_) {
    std::string path = recording_->key(r.path);
    for (const ReportedFinding& f : r.findings)
      if (!f.fingerprint.empty()) recorded_.push_back({path, {f.rule, f.text, f.occurrence, f.fingerprint}});
  }
  if (baseline_) {
    std::string path = baseline_->key(r.path);
    seen_.insert(path);
    hidden_ += std::erase_if(r.findings, [&](const ReportedFinding& f) { return !f.fingerprint.empty() && baseline_->take(path, f.fingerprint); });
  }
  writer_->file(r);
}

void LintOutput::close() { writer_->finish(); }

int LintOutput::finish() {
  if (recording_) {
    if (std::string why = Baseline::write(o_.write_baseline_file, recorded_); !why.empty())
      throw std::runtime_error(fmt::format("{}: cannot write the baseline: {}", o_.write_baseline_file, why));
    err_ << fmt::format("Wrote a baseline of {} finding(s) to {}: `lwcport {} --baseline {}` reports only new ones.\n", recorded_.size(),
                        o_.write_baseline_file, o_.command, o_.write_baseline_file);
    return 0;
  }
  if (o_.add_suppressions) {  // as writing a baseline: the point is to accept what is there
    err_ << fmt::format("Added a suppression comment to {} line(s) in {} file(s).\n", suppressions_, suppressed_files_);
    return 0;
  }
  if (baseline_) finish_baseline(o_, *baseline_, seen_, hidden_, err_);
  return o_.fail_on && writer_->failed(*o_.fail_on) ? 1 : 0;
}

namespace {

int lint(const Options& o, std::ostream& out, std::ostream& err) {
  std::unique_ptr<ConfigFinder> configs = config_finder(o);
  LintOutput output(o, out, err);
  std::vector<InputFile> files = input_files(o, *configs, err);
  if (!output.open(*configs)) return 2;
  IncludeSummaries includes;
  CodeCounter counter(files);
  LintOrder order = includes_first(files, includes);
  run_in_order<FileReport>(
      files.size(), job_count(o),
      [&](size_t i) {
        try {
          return lint_file(files[i], o, includes, order.included[i]);
        } catch (const std::exception& e) {
          return failed_file(files[i], e);
        }
      },
      [&](FileReport& r) {
        counter.add(r);
        output.file(r);
      },
      &order.order);
  output.close();
  if (!every_argument_had_code(o, counter.with_code, err)) return 2;
  return output.finish();
}

// The engine era an Unreal file was written for (its stub's LWCPORT_UE_VERSION).
int unreal_era(const std::string& text) { return static_cast<int>(infer_unreal_era(text)); }


// The same code with each accurate DoubleFloat addition replaced by its DFFast* twin: fewer flops,
// exact only within their preconditions (same signs, |a| >= |b|), which the harness's cases probe.
std::string fast_double_float_form(const std::string& text) {
  TokenText t(text);
  std::vector<Edit> edits;
  for (size_t i = 0; i < t.size(); ++i)
    if (std::string_view f = t[i]; (f == "DFAdd" || f == "DFSubtract" || f == "DFAddDemote" || f == "DFSubtractDemote") && t[i + 1] == "(")
      edits.push_back({{t.tokens[i].begin, t.tokens[i].begin + 2}, "DFFast"});
  return splice(text, edits);
}

// Runs `work` on a thread with a 1 GiB stack (reserved address space, touched only as needed):
// glslang parses and walks its tree recursively, up to its parser's depth limit (10,000), and an
// overflow there would kill the whole run. (Our own text handling no longer recurses: it once
// used std::regex, which overflowed the main thread's 8 MiB on a 2,000-member struct.)
template <typename Work>
auto on_big_stack(Work work) -> decltype(work()) {
  using Result = decltype(work());
  struct Job {
    Work* work;
    std::optional<Result> result;
    std::exception_ptr error;
  } job{&work, std::nullopt, nullptr};
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, size_t{1} << 30);
  auto entry = [](void* p) -> void* {
    auto* j = static_cast<Job*>(p);
    try {
      j->result.emplace((*j->work)());
    } catch (...) {
      j->error = std::current_exception();
    }
    return nullptr;
  };
  pthread_t thread;
  bool started = pthread_create(&thread, &attr, entry, &job) == 0;
  pthread_attr_destroy(&attr);
  if (!started) return work();
  pthread_join(thread, nullptr);
  if (job.error) std::rethrow_exception(job.error);
  return std::move(*job.result);
}

// The device and what its driver does to float arithmetic, for `verify` and `fix --verify`:
// `device` and, for functions verified side by side, more driver processes in `more`.
struct Verifier {
  std::unique_ptr<WorkerDevice> device;
  std::vector<std::unique_ptr<WorkerDevice>> more;
  DriverProbes probes;
  // Per language, the library functions that fail the library's own check on this driver.
  std::map<Lang, std::map<std::string, std::string>> library_faults;
};

// Starts `count` driver processes (at least one) and probes the first; false, with the error
// printed, when there is no device. With `check_library`, the DoubleFloat library is checked on
// the driver first (as `verify --shaderlib`, on 16,384 inputs per operation, about 0.5 s): every
// verdict rests on it, and a rewrite calling an operation that fails there is not judged.
bool start_verifier(const Options& o, Verifier& v, std::ostream& err, unsigned count = 1, bool check_library_first = false) {
  std::string error;
  v.device = WorkerDevice::start(error, o.timeout_seconds);
  if (!v.device) {
    err << "lwcport: error: " << error << '\n';
    return false;
  }
  for (unsigned i = 1; i < count; ++i)
    if (auto more = WorkerDevice::start(error, o.timeout_seconds)) v.more.push_back(std::move(more));
  if (std::string why = probe_driver(*v.device, v.probes); !why.empty()) {
    err << "lwcport: error: driver probe on " << v.device->name() << ": " << why << '\n';
    return false;
  }
  if (check_library_first) {
    LibraryCheckOptions check;
    check.inputs = 16384;
    LibraryAccuracy accuracy = check_library(*v.device, v.probes, check);
    for (Lang lang : check.langs) v.library_faults[lang] = library_faults(accuracy, lang);
  }
  return true;
}

// The functions that hold the file's findings, each once, in order: what verification runs.
// A finding outside any function (a uniform, a stage input) counts in every function that uses it.
// `facts`, when given, gets what the analysis says of the file's functions (harness.h).
std::vector<std::string> functions_with_findings(const Source& source, const AnalyzeOptions& options, Lang lang,
                                                 FunctionFacts* facts = nullptr) {
  const std::string& text = source.text();
  std::optional<FileSummary> summary;
  AnalyzeOptions with_summary = options;
  if (facts) with_summary.summary_for_includers = &summary;
  std::vector<Finding> findings = analyze(source, with_summary);
  // What lwcport says of its input (a parse note, an unused suppression) is no code to run.
  std::erase_if(findings, [](const Finding& f) { return f.rule == kInputRule || f.rule == kUnusedSuppressionRule; });
  if (facts && summary) {
    facts->returns = summary->function_returns;
    facts->globals = summary->globals;
    facts->parameters = summary->parameter_kinds;
    facts->world = &world_data(lang, options.world_sources, options.host_rebases);
  }
  std::vector<uint32_t> offsets;
  for (const Finding& finding : findings) offsets.push_back(finding.span.begin);
  std::vector<std::string> found = enclosing_functions(lang, text, offsets);
  if (facts)
    for (size_t i = 0; i < findings.size(); ++i)
      if (auto op = findings[i].facts.find("error-free"); op != findings[i].facts.end() && !found[i].empty())
        facts->error_free[found[i]] = op->second;
  std::set<std::string_view> global_names;  // what findings outside any function name
  for (size_t i = 0; i < findings.size(); ++i)
    if (found[i].empty()) global_names.insert(std::string_view(text).substr(findings[i].span.begin, findings[i].span.end - findings[i].span.begin));
  std::vector<uint32_t> uses;
  TokenText tokens(text);
  for (size_t i = 0; i < tokens.size(); ++i)
    if (tokens.ident(i) && global_names.count(tokens[i])) uses.push_back(tokens.tokens[i].begin);
  std::vector<std::string> users = enclosing_functions(lang, text, uses);
  found.insert(found.end(), users.begin(), users.end());
  std::vector<std::string> names;
  for (const std::string& name : found)
    if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

// The functions whose text a fix changed (a rewrite can follow a value into a function that holds
// no finding of its own): the original's lines each hunk of the diff removes or inserts before.
std::vector<std::string> functions_a_fix_changes(Lang lang, const std::string& original, const std::string& fixed) {
  Source source("original", original);
  std::vector<uint32_t> offsets;
  std::istringstream diff(unified_diff("f", original, fixed, 0));
  int line = 0;
  for (std::string row; std::getline(diff, row);) {
    if (row.starts_with("@@ -")) std::from_chars(row.data() + 4, row.data() + row.size(), line);
    else if (row.starts_with("-") && !row.starts_with("---")) offsets.push_back(source.offset({std::min(std::max(line++, 1), source.line_count()), 1}));
    else if (row.starts_with("+") && !row.starts_with("+++")) offsets.push_back(source.offset({std::min(std::max(line, 1), source.line_count()), 1}));
  }
  std::vector<std::string> names;
  for (const std::string& name : enclosing_functions(lang, original, offsets))
    if (!name.empty() && std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

// How the harness compiles one file: its language, stage, scene, and includes resolved as lint
// resolves them (lwcport's library from memory, Unreal's engine headers from the stub).
// A fixed text as a harness variant (UE 5.4 era), with the lines of every top-level item (a
// function, a declaration) that still holds a finding with no automatic fix: a compile error there
// is a site lwcport could not port, as the fix goldens count it.
FileVariant fixed_variant(const std::string& label, const FixOutcome& fixed, Lang lang) {
  FileVariant v{label, fixed.text, 504, {}};
  Source text("fixed", fixed.text);
  SyntaxTree tree = parse(text, lang);
  for (const Finding& f : fixed.remaining) {
    if (!f.fixes.empty() || f.not_needed) continue;
    Span item = f.span;
    for (const Node& n : tree.nodes)
      if (n.depth == 1 && n.begin <= f.span.begin && f.span.end <= n.end) item = {n.begin, n.end};
    for (int line = text.position(item.begin).line; line <= text.position(item.end).line; ++line) {
      std::string& rules = v.hand_fixes[line];
      if (rules.find(f.rule) == std::string::npos) rules += (rules.empty() ? "" : ", ") + f.rule;
    }
  }
  return v;
}

HarnessSetup harness_setup(const InputFile& file, const LoadedFile& f, Lang lang, IncludeSummaries& includes) {
  HarnessSetup setup;
  setup.lang = lang;
  setup.display = file.display;
  setup.stage = lang == Lang::glsl ? stage_from_extension(file.display).value_or(Stage::fragment) : Stage::fragment;
  setup.scene = f.options.scene;
  BuildEnvironment env = build_environment(file.path, file.display, f.source->text(), lang, file.config, includes);
  setup.unreal = env.unreal;
  setup.engine = env.engine;
  setup.include = std::move(env.include);
  setup.defines = std::move(env.defines);
  setup.force_includes = std::move(env.force_includes);
  return setup;
}

// The engine an original compiles against: the era its own code is written for (the corpus ports
// UE4 code in a project set to 5.4), unless it only compiles against the project's engine ("unreal"
// in .lwcport.json): a plugin for 5.4 that still calls LWCHackToFloat, with the engine's real
// headers read, which are 5.4's.
int original_era(const std::string& text, const AnalyzeOptions& options, const HarnessSetup& setup) {
  int written = unreal_era(text);
  if (!setup.unreal || !options.unreal || static_cast<int>(*options.unreal) == written) return written;
  FileBuild build{setup.lang, setup.display, written, false, setup.include, setup.defines, setup.force_includes};
  if (compile_file(build, text).ok) return written;
  build.unreal_version = static_cast<int>(*options.unreal);
  return compile_file(build, text).ok ? *build.unreal_version : written;
}

// `fix --verify`: runs every function with a finding as written and as fixed. "" when each fixed
// form passes; else why the fix is held back. `verified` gets one line per function that passed.
std::string verify_fix(Verifier& verifier, const InputFile& file, const LoadedFile& f, Lang lang, const FixOutcome& fixed,
                       IncludeSummaries& includes, std::vector<std::string>& verified) {
  const Source& source = *f.source;
  FunctionFacts facts;
  std::vector<std::string> names = functions_with_findings(source, f.options, lang, &facts);
  for (const std::string& name : functions_a_fix_changes(lang, source.text(), fixed.text))
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  if (names.empty()) return "no function of the file holds a finding or is changed by the fix, so there is nothing to run";
  HarnessSetup setup = harness_setup(file, f, lang, includes);
  setup.facts = std::move(facts);
  setup.library_faults = verifier.library_faults[lang];
  std::vector<FileVariant> variants = {{"original (float32)", source.text(), original_era(source.text(), f.options, setup), {}},
                                       fixed_variant("fixed", fixed, lang)};
  for (const std::string& name : names) {
    FunctionResult r = on_big_stack([&] { return verify_function(*verifier.device, verifier.probes, setup, name, variants); });
    const VariantResult &v = r.variants.back(), &original = r.variants.front();
    // Input-limited: right on what it is handed, but a value its callers pass (unchanged by the
    // fix) is float32; written when it is no further from the reference than the original was.
    // (Often it is further: a float32 position minus a float32 camera rounds on one grid and the
    // roundings cancel, while minus an exact camera they do not.)
    bool no_worse = original.measured && v.worst_over_target <= original.worst_over_target + 1;
    if (v.input_limited() && !no_worse)
      return fmt::format("the rewrite of `{}` is right on the inputs it is handed, but further from the float64 reference than "
                         "the original (worst {:.3g} cm against {:.3g} cm) while float32 values its callers pass still round "
                         "({}): widen them first; worst {}", name, v.max_error, original.max_error, v.inherited_rounding, v.worst);
    if (!v.passed() && !v.input_limited())
      return fmt::format("the rewrite of `{}` did not pass verification on {}: {}{}", name, verifier.device->name(), v.status,
                         v.worst.empty() ? "" : "; worst " + v.worst);
    std::string timing = fmt::format("{:.3g} ns per invocation, the original {:.3g}", v.ns_per_invocation, original.ns_per_invocation);
    if (v.passed() && r.reference.starts_with("exact"))
      verified.push_back(fmt::format("verified on {}: the rewrite of `{}` is error-free on every input: high + low is the exact {} "
                                     "and the pair canonical ({})", verifier.device->name(), name,
                                     setup.facts.error_free.at(name) == "product" ? "product" : setup.facts.error_free.at(name) == "split" ? "value" : "sum", timing));
    else if (v.passed() && !v.world_outputs)
      verified.push_back(fmt::format("verified on {}: the rewrite of `{}` has unitless results within 2^-12 of the float64 "
                                     "reference (max {:.3g} float32 ULPs; {})", verifier.device->name(), name, v.max_ulps, timing));
    else if (v.passed())
      verified.push_back(fmt::format("verified on {}: the rewrite of `{}` is within {} of the float64 reference (max {:.3g} cm; {})",
                                     verifier.device->name(), name, format_distance(setup.scene.precision), v.max_error, timing));
    else
      verified.push_back(fmt::format("verified on {}: the rewrite of `{}` computes within {} on the inputs it is handed (worst "
                                     "{:.3g} cm) and is no further from the float64 reference than the original; float32 values "
                                     "its callers pass still round ({}): widen them there; {}",
                                     verifier.device->name(), name, format_distance(setup.scene.precision), v.own_max_error,
                                     v.inherited_rounding, timing));
  }
  return "";
}

// `fix --check-build`: the fixed text must compile where the original did (glslang; Unreal code
// against the stub of the era the project builds against, GLSL for OpenGL or else Vulkan).
// Errors only in code that still holds a finding lwcport could not port make it incomplete, not
// broken: that code needs a hand port whatever lwcport does. UE4 code built against UE 5.x does
// not compile until then, so its original is also tried against the era it was written for.
struct BuildCheck {
  enum class Outcome { compiles, incomplete, breaks, unchecked } outcome;
  std::string detail;  // where it was compiled, or the first error
  bool compiler_failed = false;  // unchecked because glslang crashed or hung, not because of the code
};

BuildCheck check_build(const InputFile& file, const LoadedFile& f, Lang lang, const std::string& original,
                       const FixOutcome& fixed, IncludeSummaries& includes) {
  HarnessSetup setup = harness_setup(file, f, lang, includes);
  FileBuild target{lang, file.display, std::nullopt, false, setup.include, setup.defines, setup.force_includes};
  std::string where = "glslang";
  std::optional<UnrealEra> written;
  if (setup.engine) {
    written = infer_unreal_era(original);
    where += fmt::format(", against the engine's headers ({}; lwcport stands in for what the shader compiler generates)", era_name(*setup.engine));
  } else if (setup.unreal) {
    written = infer_unreal_era(original);
    UnrealEra era = f.options.unreal.value_or(*written);
    target.unreal_version = static_cast<int>(era);
    where += fmt::format(", against lwcport's {} stub", era_name(era));
  }
  auto first_error = [&](const CompileResult& r) {
    if (r.messages.empty()) return std::string("no message");
    const CompileMessage& m = r.messages.front();
    return fmt::format("{}line {}: {}", m.source == file.display ? "" : m.source + ", ", m.line, m.text);
  };
  CompileResult was = compile_file(target, original);
  if (!was.ok && lang == Lang::glsl) {
    target.vulkan = true;
    if (CompileResult vulkan = compile_file(target, original); vulkan.ok) was = vulkan;
    else target.vulkan = false;
  }
  if (!was.ok && !setup.engine && written && static_cast<int>(*written) != *target.unreal_version) {
    FileBuild own = target;
    own.unreal_version = static_cast<int>(*written);
    if (compile_file(own, original).ok) was.ok = true;
  }
  if (!was.crashed.empty()) return {BuildCheck::Outcome::unchecked, was.crashed + " on the original", true};
  // Code written for an older engine than the one the project builds against need not compile
  // against its headers: that is what the port is for, so the fixed file is still checked.
  bool older = setup.engine && written && *written != *setup.engine;
  if (!was.ok && !older) return {BuildCheck::Outcome::unchecked, setup.engine ? where + ": " + first_error(was) : first_error(was)};
  if (lang == Lang::glsl) where += target.vulkan ? ", for Vulkan" : ", for OpenGL";
  CompileResult now = compile_file(target, fixed.text);
  if (!now.crashed.empty()) return {BuildCheck::Outcome::unchecked, now.crashed + " on the fixed file", true};
  if (now.ok) return {BuildCheck::Outcome::compiles, was.ok ? where : where + fmt::format(", which the original ({} code) did not", era_name(*written))};
  // An include the harness cannot find (a header the engine generates that lwcport does not
  // stand in for) says nothing of the fix.
  for (const CompileMessage& m : now.messages)
    if (m.text.find("Could not process include directive") != std::string::npos)
      return {BuildCheck::Outcome::unchecked, where + ": " + first_error(CompileResult{false, "", {m}, {}})};
  // A first error in a header (later ones may follow from it): the original's did not compile
  // either (the harness cannot build this file), or the fix broke what the headers expect of it.
  if (now.messages.empty() || now.messages.front().source != file.display)
    return {was.ok ? BuildCheck::Outcome::breaks : BuildCheck::Outcome::unchecked, where + ": " + first_error(now)};
  std::map<int, std::string> by_hand = fixed_variant("fixed", fixed, lang).hand_fixes;
  for (const CompileMessage& m : now.messages)
    if (m.source == file.display && !by_hand.count(m.line)) {
      if (!was.ok)  // nothing compiled before the fix either: the port is unfinished, not broken
        return {BuildCheck::Outcome::incomplete, fmt::format("{}: {}; the original ({} code) does not compile against them either", where,
                                                             first_error(now), era_name(*written))};
      return {BuildCheck::Outcome::breaks, where + ": " + first_error(now)};
    }
  int line = now.messages.front().line;
  return {BuildCheck::Outcome::incomplete,
          fmt::format("{}: line {} is in code lwcport could not port ({})", where, line, by_hand.count(line) ? by_hand[line] : "")};
}

struct FixedFile {
  std::filesystem::path path;
  FileReport report;   // what remains, plus any write problem
  std::string diff;    // --diff
  int applied = 0;      // fixes
  int resolved = 0;     // findings they took away (FixOutcome::resolved)
  int unsafe_left = 0;  // remaining findings whose fix is unsafe
  bool changed = false;
  // The fixed text includes lwcport's library, which must then exist beside it with these names.
  std::optional<Lang> library_lang;
  std::set<std::string> library_names;
  std::optional<BuildCheck::Outcome> build;  // --check-build
  // A fixed text that includes the library waits to be written until the library is (fix()).
  std::optional<LoadedFile> pending;
  std::string pending_text;
  std::optional<std::string> text_out;  // standard input: the text for standard output, fixed or not
};

// The library file one folder of fixed files includes (lwc_doublefloat.hlsl / .glsl).
struct LibraryFile {
  std::filesystem::path path;
  std::string display;
  Lang lang;
  std::set<std::string> names;
};

// Nothing was written: the report is the original file's findings after `why`, not the unwritten result's.
void keep_original(FixedFile& out, const Source& source, const AnalyzeOptions& options, const Finding& why) {
  out.changed = false;
  out.applied = 0;
  out.resolved = 0;
  out.diff.clear();
  out.report.findings.clear();
  out.report.findings.push_back(locate(source, why));
  for (const Finding& finding : analyze(source, options)) out.report.findings.push_back(locate(source, finding));
  out.library_lang.reset();
}

FixedFile fix_file(const InputFile& file, const Options& o, IncludeSummaries& includes, Verifier* verifier) {
  FixedFile out;
  LoadedFile f = load(file, o, includes);
  if (f.problem) {
    out.report = std::move(*f.problem);
    return out;
  }
  const Source& source = *f.source;
  if (file.content) out.text_out = source.text();
  FixOutcome fixed = fix_source(source, f.options, o.unsafe_fixes);
  out.path = file.path;
  out.report.path = file.display;
  out.report.has_code = holds_shader_code(source, f.options);
  out.applied = fixed.applied;
  out.resolved = fixed.resolved;
  out.changed = fixed.text != source.text();
  Source result(file.display, fixed.text);
  for (const Finding& finding : fixed.remaining) {
    out.report.findings.push_back(locate(result, finding));
    if (!finding.fixes.empty() && finding.fixes.front().applicability == Applicability::unsafe) ++out.unsafe_left;
  }
  if (!fixed.converged) {
    out.report.findings.push_back(locate(result, input_finding(Severity::warning, 0, "fixes kept changing the file; stopped after 10 rounds",
                                                                "please report this file: a fix should apply once")));
  }
  add_fingerprints(out.report, result, o.report.format == Format::sarif);
  if (!out.changed) return out;
  std::optional<Lang> lang = language_for(source, f.options);
  if (verifier && lang) {
    std::vector<std::string> verified;
    if (std::string why = on_big_stack([&] { return verify_fix(*verifier, file, f, *lang, fixed, includes, verified); }); !why.empty()) {
      keep_original(out, source, f.options, input_finding(Severity::warning, 0, "fix held back: " + why,
                                                          "run `lwcport verify` on the file for every variant's numbers"));
      return out;
    }
    for (const std::string& line : verified) out.report.findings.push_back(locate(result, input_finding(Severity::note, 0, line, "")));
  }
  if (o.check_build && lang) {
    BuildCheck check = check_build(file, f, *lang, source.text(), fixed, includes);
    out.build = check.outcome;
    if (check.outcome == BuildCheck::Outcome::breaks) {
      keep_original(out, source, f.options, input_finding(Severity::warning, 0, "fix held back: the fixed file does not compile where the original did (" + check.detail + ")",
                                                          "apply the fixes one by one (`lwcport fix --diff`) to see which one needs a hand port"));
      return out;
    }
    std::string note = check.outcome == BuildCheck::Outcome::compiles     ? "build checked: the fixed file compiles as the original did (" + check.detail + ")"
                       : check.outcome == BuildCheck::Outcome::incomplete ? "build checked: the fixed file compiles except where lwcport could not port the code (" + check.detail + "); port that by hand"
                       : check.compiler_failed ? "build not checked: " + check.detail
                                                                          : "build not checked: the original does not compile where lwcport builds it (" + check.detail + ")";
    out.report.findings.push_back(locate(result, input_finding(Severity::note, 0, note, "")));
  }
  if (lang && fixed.text.find("\"" + library_file_name(*lang) + "\"") != std::string::npos) {
    out.library_lang = lang;
    out.library_names = library_names_used(*lang, fixed.text);
  }
  if (o.diff) {
    out.diff = unified_diff(file.display, source.text(), fixed.text);
    return out;
  }
  if (file.content) {  // standard input: the fixed text goes to standard output, nothing is written
    if (out.library_lang)
      out.report.findings.push_back(locate(result, input_finding(Severity::warning, 0,
          fmt::format("the fixed text includes `{}`, which `lwcport fix` writes beside a file but not for standard input",
                      library_file_name(*out.library_lang)),
          "run `lwcport fix` on the file itself once, so the library is written beside it")));
    out.library_lang.reset();
    out.text_out = std::move(fixed.text);
    return out;
  }
  if (out.library_lang) {
    out.pending_text = std::move(fixed.text);
    out.pending.emplace(std::move(f));
    return out;
  }
  std::string why = replace_file(file.path, source.text(), fixed.text, o.force);
  if (!why.empty())
    keep_original(out, source, f.options, input_finding(Severity::error, 0, "cannot write the fixes: " + why, "the other files were still fixed"));
  return out;
}

// Writes (or, with --diff, prints) the library file of one folder: what the fixed files there
// call, plus what an earlier run's file already holds (files fixed then still include it).
// False (with the reason printed) when the library could not be written.
bool write_library(const LibraryFile& lib, const Options& o, std::ostream& out, std::ostream& err) {
  std::optional<std::string> existing;
  bool exists = std::filesystem::exists(lib.path);
  if (exists) {
    ReadResult r = read_file(lib.path, SIZE_MAX);
    if (!r.error.empty()) {
      err << fmt::format("{}: cannot read: {}; the fixed files need it\n", lib.display, r.error);
      return false;
    }
    existing = std::move(r.text);
  }
  std::optional<std::string> written = library_file_text(lib.lang, lib.names, existing);
  if (!written) {
    err << fmt::format("{}: exists and was not written by lwcport; not changed (the fixed files need: {})\n", lib.display,
                       fmt::join(lib.names, ", "));
    return false;
  }
  std::string before = existing.value_or(""), after = std::move(*written);
  if (after == before) return true;
  if (o.diff) {
    std::string diff = unified_diff(lib.display, before, after);
    if (!exists) diff.replace(0, diff.find('\n'), "--- /dev/null");  // a new file, as git shows one
    out << diff;
    return true;
  }
  std::string why = exists ? replace_file(lib.path, before, after, o.force) : create_file(lib.path, after);
  if (!why.empty()) {
    err << fmt::format("{}: cannot write the shader library: {}; the files that need it were not changed\n", lib.display, why);
    return false;
  }
  std::set<std::string> names = lib.names;  // what the fixed files call and what the file kept
  if (existing) names.merge(library_names_used(lib.lang, *existing));
  err << fmt::format("Wrote {} ({} name(s) and what they use).\n", lib.display, names.size());
  return true;
}

int fix(const Options& o, std::ostream& out, std::ostream& err) {
  remove_temporary_files_on_signals();
  std::unique_ptr<ConfigFinder> configs = config_finder(o);
  std::vector<InputFile> files = input_files(o, *configs, err);
  // --verify: one device, used by one file at a time (started before any thread: it forks).
  std::optional<Verifier> verifier;
  if (o.verify && !start_verifier(o, verifier.emplace(), err, 1, true)) return 2;
  ReportTarget target;
  ReportOptions ro;
  if (!open_target(o, *configs, out, err, target, ro)) return 2;
  // With --diff the diff is the output; the remaining findings are not repeated.
  // `fix -`: the fixed text is the output; what remains is reported on standard error.
  bool to_stdout = files.size() == 1 && files[0].content && !o.diff;
  if (to_stdout) ro.color = o.color == "always";
  std::optional<ReportWriter> writer;
  if (!o.diff) writer.emplace(to_stdout ? err : *target.stream, ro);
  IncludeSummaries includes;
  int applied = 0, resolved = 0, changed_files = 0, unsafe_left = 0;
  std::map<BuildCheck::Outcome, int> builds;
  CodeCounter counter(files);
  std::map<std::string, LibraryFile> libraries;  // by path
  std::vector<FixedFile> done;                    // in path order
  run_in_order<FixedFile>(
      files.size(), verifier ? 1 : job_count(o),
      [&](size_t i) {
        try {
          return fix_file(files[i], o, includes, verifier ? &*verifier : nullptr);
        } catch (const std::exception& e) {
          FixedFile failed;
          failed.report = failed_file(files[i], e);
          return failed;
        }
      },
      [&](FixedFile& r) {
        if (r.library_lang) {
          std::string name = library_file_name(*r.library_lang);
          std::filesystem::path dir = std::filesystem::path(r.path).parent_path();
          std::string display = (std::filesystem::path(r.report.path).parent_path() / name).generic_string();
          LibraryFile& lib = libraries.try_emplace((dir / name).string(), LibraryFile{dir / name, display, *r.library_lang, {}}).first->second;
          lib.names.insert(r.library_names.begin(), r.library_names.end());
        }
        done.push_back(std::move(r));
      });
  // A library is written before the files that include it; a file whose library could not be
  // written is not changed, so no file ever includes a library that is missing.
  std::set<std::string> missing_libraries;
  if (!o.diff)
    for (const auto& [path, lib] : libraries)
      if (!write_library(lib, o, *target.stream, err)) missing_libraries.insert(path);
  for (FixedFile& r : done) {
    if (r.pending) {
      const Source& source = *r.pending->source;
      std::string library = (std::filesystem::path(r.path).parent_path() / library_file_name(*r.library_lang)).string();
      std::string why = missing_libraries.count(library) ? "the library it includes could not be written"
                                                         : replace_file(r.path, source.text(), r.pending_text, o.force);
      if (!why.empty())
        keep_original(r, source, r.pending->options,
                      input_finding(Severity::error, 0, "cannot write the fixes: " + why, "the other files were still fixed"));
      r.pending.reset();
    }
    applied += r.applied;
    resolved += r.resolved;
    changed_files += r.changed;
    unsafe_left += r.unsafe_left;
    if (r.build) ++builds[*r.build];
    counter.add(r.report);
    if (o.diff) *target.stream << r.diff;
    else writer->file(r.report);
    if (to_stdout && r.text_out) *target.stream << *r.text_out;
  }
  if (o.diff)
    for (const auto& [path, lib] : libraries) write_library(lib, o, *target.stream, err);
  bool arguments_ok = every_argument_had_code(o, counter.with_code, err);
  std::string unsafe = unsafe_left ? fmt::format(" {} more fix(es) are unsafe: rerun with --unsafe-fixes.", unsafe_left) : "";
  if (applied && !o.verify)
    unsafe += fmt::format(" {} not verified on a device: `lwcport verify` measures each rewrite against a float64 reference, "
                          "and `fix --verify` applies only those that pass.", applied == 1 ? "It was" : "They were");
  if (o.check_build)
    err << fmt::format("Build check: {} fixed file(s) compile as their originals did, {} compile except in code left to port by hand, "
                       "{} held back (the fix broke the build), {} not checked (the original does not compile where lwcport builds it).\n",
                       builds[BuildCheck::Outcome::compiles], builds[BuildCheck::Outcome::incomplete],
                       builds[BuildCheck::Outcome::breaks], builds[BuildCheck::Outcome::unchecked]);
  if (o.diff) {
    err << fmt::format("Would fix {} finding(s) in {} file(s).{}\n", resolved, changed_files, unsafe);
    if (!arguments_ok) return 2;
    return changed_files && o.fail_on ? 1 : 0;  // like a linter: changes to make fail the run
  }
  writer->finish();
  err << fmt::format("Fixed {} finding(s) in {} file(s).{}\n", resolved, changed_files, unsafe);
  if (!arguments_ok) return 2;
  return o.fail_on && writer->failed(*o.fail_on) ? 1 : 0;
}

// Each syntax error with its line and a caret.
std::string syntax_error_lines(const Source& src, const std::set<SyntaxError>& errors) {
  std::string out;
  for (const SyntaxError& e : errors) {
    Position pos = src.position(e.offset);
    std::string line(src.line_text(pos.line));
    for (char& c : line) if (c == '\t') c = ' ';
    out += fmt::format("{}:{}:{}: syntax error: {}\n  {}\n  {}^\n", src.path(), pos.line, pos.column, e.what, line,
                       std::string(pos.column - 1, ' '));
  }
  return out;
}

// `lwcport parse`: each file's syntax errors, as lint counts them (syntax_errors: the same parse,
// the same macros, the project's and its includes', the same count).
int parse_only(const Options& o, std::ostream& out, std::ostream& err) {
  std::unique_ptr<ConfigFinder> configs = config_finder(o);
  std::vector<SkippedFile> skipped;
  std::vector<InputFile> files = discover(o.paths.empty() ? std::vector<std::string>{"."} : o.paths, *configs, &skipped);
  std::vector<size_t> errors(files.size());
  std::vector<std::string> details(files.size());
  std::vector<char> has_code(files.size(), 0);  // written by worker threads: not vector<bool>
  std::atomic<size_t> bytes{0};
  IncludeSummaries includes;
  auto parse_file = [&](size_t i) {
    const ProjectConfig& config = *files[i].config;
    ReadResult r = read_file(files[i].path, config.max_file_bytes);
    if (!r.error.empty() || r.too_large) return;
    AnalyzeOptions a = analysis_options(config);
    a.lang = o.lang;
    Source src(files[i].display, std::move(r.text));
    if (shader_code(src, a).empty(src)) return;
    has_code[i] = true;
    bytes += src.text().size();
    FileSummary included;
    if (src.text().find("include") != std::string::npos) {
      included.macros = includes.included_macros(files[i].path, src.text(), config);
      a.includes = &included;
    }
    std::set<SyntaxError> found = syntax_errors(src, a);
    errors[i] = found.size();
    if (o.verbose) details[i] = syntax_error_lines(src, found);
  };
  parallel_for(files.size(), job_count(o), [&](size_t i) {
    try {
      parse_file(i);
    } catch (const std::exception& e) {
      errors[i] = 1;
      details[i] = fmt::format("{}: internal error: {}\n", files[i].display, e.what());
      has_code[i] = true;
    }
  });
  size_t with_errors = 0, parsed = 0;
  std::vector<size_t> with_code;
  for (size_t i = 0; i < files.size(); ++i) {
    if (with_code.size() <= files[i].argument) with_code.resize(files[i].argument + 1);
    if (!has_code[i]) {
      skipped.push_back({files[i].display, files[i].error.empty() ? "no shader code in it" : files[i].error});
      continue;
    }
    ++parsed;
    ++with_code[files[i].argument];
    if (errors[i]) {
      ++with_errors;
      out << fmt::format("{}: {} syntax error(s)\n", files[i].display, errors[i]) << details[i];
    }
  }
  if (o.verbose)
    for (const SkippedFile& s : skipped) out << fmt::format("{}: skipped: {}\n", s.display, s.why);
  out << fmt::format("Parsed {} file(s), {} bytes; {} with syntax errors; {} skipped{}.\n", parsed, bytes.load(), with_errors,
                     skipped.size(), skipped.empty() || o.verbose ? "" : " (--verbose lists them)");
  if (!every_argument_had_code(o, with_code, err)) return 2;
  return with_errors ? 1 : 0;
}

// `lwcport verify PATHS`: every function with a finding, in its original form and each rewrite.
int verify_functions(const Options& o, ConfigFinder& configs, Verifier& verifier, std::ostream& out, std::ostream& err) {
  auto start = std::chrono::steady_clock::now();
  std::vector<InputFile> files = input_files(o, configs, err);
  IncludeSummaries includes;
  std::vector<FunctionResult> results;
  std::vector<std::string> unverified;  // files with findings where no function ran at all
  std::vector<size_t> with_code;         // per command-line argument
  // What to run, gathered first so that progress can count it: per file, its functions and variants.
  struct FileWork {
    const InputFile* file;
    HarnessSetup setup;
    std::vector<std::string> names;
    std::vector<FileVariant> variants;
  };
  std::vector<FileWork> work;
  size_t total = 0;
  for (const InputFile& file : files) {
    LoadedFile f = load(file, o, includes);
    if (f.problem) {
      for (const ReportedFinding& finding : f.problem->findings) err << fmt::format("{}: {}\n", file.display, finding.message);
      continue;
    }
    const Source& source = *f.source;
    std::optional<Lang> lang = language_for(source, f.options);
    if (!lang) continue;
    if (with_code.size() <= file.argument) with_code.resize(file.argument + 1);
    ++with_code[file.argument];
    FunctionFacts facts;
    std::vector<std::string> names = functions_with_findings(source, f.options, *lang, &facts);
    HarnessSetup setup = harness_setup(file, f, *lang, includes);
    std::vector<FileVariant> variants = {{"original (float32)", source.text(), original_era(source.text(), f.options, setup), {}}};
    for (auto [strategy, label] : {std::pair{Strategy::translated, "translated world"}, std::pair{Strategy::df, "DoubleFloat"}}) {
      AnalyzeOptions a = f.options;
      a.strategy = strategy;
      FixOutcome fixed = fix_source(source, a, true);
      bool seen = false;
      for (const FileVariant& v : variants) seen |= v.text == fixed.text;
      if (seen) continue;
      variants.push_back(fixed_variant(label, fixed, *lang));
      for (const std::string& name : functions_a_fix_changes(*lang, source.text(), fixed.text))
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
    if (names.empty()) continue;
    if (variants.size() == 2 && variants[1].label != "original (float32)") variants[1].label = "fixed";
    for (size_t i = 0, n = variants.size(); i < n; ++i)
      if (std::string fast = fast_double_float_form(variants[i].text); fast != variants[i].text)
        variants.push_back({variants[i].label.substr(0, variants[i].label.find(" (")) + ", DFFast*", fast, variants[i].ue_version,
                            variants[i].hand_fixes, false});
    total += names.size();
    work.push_back({&file, std::move(setup), std::move(names), std::move(variants)});
    work.back().setup.facts = std::move(facts);
    work.back().setup.library_faults = verifier.library_faults[*lang];
  }
  // Functions run side by side, one per driver process; results keep their order. Progress on a
  // terminal (standard error), one line rewritten in place; nothing when redirected.
  std::vector<std::pair<const FileWork*, const std::string*>> jobs;
  for (const FileWork& w : work)
    for (const std::string& name : w.names) jobs.emplace_back(&w, &name);
  results.resize(jobs.size());
  std::vector<WorkerDevice*> devices = {verifier.device.get()};
  for (const auto& d : verifier.more) devices.push_back(d.get());
  bool progress = ::isatty(STDERR_FILENO);
  std::atomic<size_t> next = 0;
  size_t done = 0;
  std::mutex progress_lock;
  auto drive = [&](WorkerDevice& device) {
    for (size_t i; (i = next++) < jobs.size();) {
      const FileWork* w = jobs[i].first;  // not a structured binding: clang 14 cannot capture one
      const std::string* name = jobs[i].second;
      if (progress) {
        std::lock_guard lock(progress_lock);
        err << fmt::format("\r\x1b[K[{}/{}] {}: {}", ++done, total, w->file->display, *name) << std::flush;
      }
      results[i] = on_big_stack([&] { return verify_function(device, verifier.probes, w->setup, *name, w->variants); });
    }
  };
  std::vector<std::thread> threads;
  for (size_t d = 1; d < devices.size() && d < jobs.size(); ++d) threads.emplace_back(drive, std::ref(*devices[d]));
  drive(*devices[0]);
  for (std::thread& t : threads) t.join();
  for (size_t i = 0, j = 0; i < work.size(); ++i) {
    bool any_ran = false;
    for (size_t k = 0; k < work[i].names.size(); ++k, ++j)
      for (const auto& v : results[j].variants) any_ran |= v.measured;
    if (!any_ran) unverified.push_back(work[i].file->display);
  }
  if (progress && done) err << "\r\x1b[K" << std::flush;
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.report.format == Format::json) print_functions_json(out, verifier.device->name(), verifier.probes, results, wall);
  else print_functions_text(out, verifier.device->name(), verifier.probes, results, wall, o.report.explain);
  for (const std::string& path : unverified)
    err << fmt::format("lwcport: {}: nothing in it could be verified (no function ran; the reasons are above)\n", path);
  if (!every_argument_had_code(o, with_code, err)) return 2;
  if (!o.fail_on) return 0;
  if (!unverified.empty()) return 1;
  for (const FunctionResult& r : results)
    for (size_t i = 1; i < r.variants.size(); ++i)
      if (r.variants[i].refuted()) return 1;
  return 0;
}

int verify(const Options& o, std::ostream& out, std::ostream& err) {
  // One driver process per core for functions verified side by side (the library check uses one).
  Verifier verifier;
  if (!start_verifier(o, verifier, err, o.shaderlib ? 1 : job_count(o), !o.shaderlib)) return 2;
  std::unique_ptr<ConfigFinder> configs = config_finder(o);
  ReportTarget target;
  ReportOptions ro;
  if (!open_target(o, *configs, out, err, target, ro)) return 2;
  if (!o.shaderlib) return verify_functions(o, *configs, verifier, *target.stream, err);
  LibraryCheckOptions options;
  LibraryAccuracy accuracy = check_library(*verifier.device, verifier.probes, options);
  const std::string& name = verifier.device->name();
  if (o.report.format == Format::json) print_library_json(*target.stream, name, verifier.probes, accuracy, options.inputs);
  else print_library_text(*target.stream, name, verifier.probes, accuracy, options.inputs);
  return accuracy.failed() ? 1 : 0;
}

// The scenes the report prices the port under: the bundled profiles and Unreal's full world.
std::vector<Scene> report_scenes(const Options& o) {
  std::vector<Scene> scenes{Scene{}};
  for (const EmbeddedFile& f : embedded_scene_files()) scenes.push_back(parse_scene(f.text, std::string(f.name)));
  if (o.scene && std::none_of(scenes.begin(), scenes.end(), [&](const Scene& s) { return s.name == o.scene->name; })) scenes.push_back(*o.scene);
  return scenes;
}

// --history / --since: the counts at each commit, each distinct file content linted once.
std::vector<HistoryPoint> report_history(const Options& o, ConfigFinder& configs, std::ostream& err) {
  std::vector<std::string> args = o.paths.empty() ? std::vector<std::string>{"."} : o.paths;
  fs::path top = git_top(fs::is_directory(args[0]) ? fs::path(args[0]) : fs::absolute(args[0]).parent_path());
  std::vector<std::string> specs;
  for (const std::string& a : args) {
    std::string rel = fs::absolute(a).lexically_normal().lexically_relative(top).generic_string();
    specs.push_back(rel.empty() || rel == "." ? "." : rel);
  }
  std::vector<CommitFiles> commits = git_history(top, specs, o.history, o.since);
  // Each distinct (path, content) a shader: linted once, however many commits hold it.
  std::map<std::pair<std::string, std::string>, std::pair<std::map<std::string, size_t>, size_t>> counts;
  std::set<std::string> blobs;
  for (const CommitFiles& c : commits)
    for (const auto& [path, blob] : c.files) {
      std::shared_ptr<const ProjectConfig> config = configs.for_dir((top / path).parent_path());
      if (!config->formats.for_path(path) || config->excluded(top / path, false)) continue;
      if (counts.emplace(std::pair{path, blob}, std::pair<std::map<std::string, size_t>, size_t>{}).second) blobs.insert(blob);
    }
  std::map<std::string, std::string> texts = git_blobs(top, blobs);
  std::vector<std::pair<std::string, std::string>> work;
  for (const auto& [key, value] : counts) work.push_back(key);
  IncludeSummaries includes;
  parallel_for(work.size(), job_count(o), [&](size_t i) {
    const auto& [path, blob] = work[i];
    auto& [by_rule, markers] = counts.at(work[i]);
    try {
      std::shared_ptr<const ProjectConfig> config = configs.for_dir((top / path).parent_path());
      AnalyzeOptions a = analysis_options(*config);
      a.lang = o.lang;
      if (!o.select.empty()) a.select = o.select;
      a.ignore.insert(o.ignore.begin(), o.ignore.end());
      if (o.scene) a.scene = o.scene->for_path(path);
      Source source(path, texts.count(blob) ? texts.at(blob) : std::string());
      FileSummary summary;  // the includes as the working tree has them
      a.engine_file = engine_file(includes.canonical(top / path), *config);
      if (source.text().find("include") != std::string::npos) {
        summary = includes.for_file(top / path, source.text(), *config);
        a.includes = &summary;
      }
      for (const Finding& f : analyze(source, a)) {
        ++by_rule[f.rule];
        markers += f.rule == "lwc-hack-marker";
      }
    } catch (const std::exception& e) {
      ++by_rule[std::string(kInputRule)];
    }
  });
  std::vector<HistoryPoint> out;
  for (const CommitFiles& c : commits) {
    HistoryPoint h{c.commit, c.date, c.subject, {}, 0, 0};
    for (const auto& [path, blob] : c.files) {
      auto it = counts.find({path, blob});
      if (it == counts.end()) continue;
      for (const auto& [rule, n] : it->second.first) h.by_rule[rule] += n, h.total += n;
      h.markers += it->second.second;
    }
    out.push_back(std::move(h));
  }
  err << fmt::format("History: {} commit(s), {} distinct file version(s) linted.\n", commits.size(), work.size());
  return out;
}

int run_host_program(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// report --host: `lwcport host`'s findings as files of their own era, and each one that feeds a
// shader parameter paired with the shader files that read that parameter.
void add_host_code(const Options& o, const std::vector<InputFile>& shaders, MigrationReport& rep, std::vector<std::vector<FileEntry>>& per_scene,
                   std::ostream& err) {
  std::vector<std::string> args{"host"};
  args.insert(args.end(), o.host_paths.begin(), o.host_paths.end());
  for (const char* a : {"--format", "json", "--fail-on", "none"}) args.push_back(a);
  if (!o.build_dir.empty()) args.insert(args.end(), {"-p", o.build_dir});
  if (!o.config_file.empty()) args.insert(args.end(), {"--config", o.config_file});
  if (o.isolated) args.push_back("--isolated");
  std::ostringstream json, errors;
  int code = host_command ? host_command(parse_options(args), json, errors) : run_host_program(args, json, errors);
  err << errors.str();
  if (code != 0) throw std::runtime_error("`lwcport host` failed on the --host paths; no report was written");
  std::map<std::string, std::vector<ReportedFinding>> by_file;
  nlohmann::json parsed = nlohmann::json::parse(json.str());
  for (const auto& f : parsed.at("findings")) by_file[f.at("path").get<std::string>()].push_back(finding_from_json(f));
  rep.host = true;
  std::set<std::string> parameters;
  for (auto& [path, findings] : by_file) {
    for (const ReportedFinding& f : findings)
      if (f.facts.count("shader-parameter")) {
        parameters.insert(f.facts.at("shader-parameter"));
        rep.host_pairs.push_back({fmt::format("{}:{}", path, f.start.line), f.rule, f.facts.at("shader-parameter"), f.facts.at("port"), {}});
      }
    FileEntry entry{path, kHostEra, std::move(findings)};
    for (auto& scene : per_scene) scene.push_back(entry);
    rep.files.push_back(std::move(entry));
  }
  std::sort(rep.files.begin(), rep.files.end(), [](const FileEntry& a, const FileEntry& b) { return a.path < b.path; });
  // Which shader files read each parameter: its name as a whole word in their text.
  std::map<std::string, std::vector<std::string>> readers;
  for (const InputFile& file : shaders) {
    std::string text = file.content ? *file.content : read_file(file.path, SIZE_MAX).text;
    for (const std::string& p : parameters)
      for (size_t at = text.find(p); at != std::string::npos; at = text.find(p, at + 1)) {
        bool starts = at == 0 || !ident_char(text[at - 1]), ends = at + p.size() >= text.size() || !ident_char(text[at + p.size()]);
        if (starts && ends) {
          readers[p].push_back(file.display);
          break;
        }
      }
  }
  for (HostPair& pair : rep.host_pairs) pair.shader_files = readers[pair.parameter];
}

int report(const Options& o, std::ostream& out, std::ostream& err) {
  std::unique_ptr<ConfigFinder> configs = config_finder(o);
  std::vector<InputFile> files = input_files(o, *configs, err);
  std::vector<Scene> scenes = report_scenes(o);
  MigrationReport rep;
  rep.scene = o.scene ? o.scene->name : Scene{}.name;
  std::vector<std::optional<FileEntry>> entries(files.size());
  std::vector<std::vector<FileEntry>> per_scene(scenes.size(), std::vector<FileEntry>(files.size()));
  IncludeSummaries includes;
  CodeCounter counter(files);
  LintOrder order = includes_first(files, includes);
  run_in_order<FileReport>(
      files.size(), job_count(o),
      [&](size_t i) {
        FileReport r;
        try {
          r = lint_file(files[i], o, includes, order.included[i]);
          for (size_t s = 0; s < scenes.size(); ++s) {
            if (scenes[s].name == rep.scene) {  // the report's own scene: its analysis is the one above
              per_scene[s][i] = {r.path, r.era, r.findings};
              continue;
            }
            Options under = o;
            under.scene = scenes[s];
            FileReport p = lint_file(files[i], under, includes, false);
            per_scene[s][i] = {p.path, p.era, std::move(p.findings)};
          }
        } catch (const std::exception& e) {
          r = failed_file(files[i], e);
        }
        return r;
      },
      [&](FileReport& r) {
        counter.add(r);
        if (!r.has_code) return;
        for (const ReportedFinding& f : r.findings)
          if (f.rule == "lwc-hack-marker") rep.markers.push_back(marker_site(r.path, f));
        rep.files.push_back({r.path, r.era, std::move(r.findings)});
      },
      &order.order);
  if (!every_argument_had_code(o, counter.with_code, err)) return 2;
  if (!o.host_paths.empty()) add_host_code(o, files, rep, per_scene, err);
  for (size_t s = 0; s < scenes.size(); ++s) rep.scenes.push_back(scene_cost(scenes[s].name, per_scene[s]));
  if (o.history || !o.since.empty()) rep.history = report_history(o, *configs, err);
  if (o.verify) {
    Verifier verifier;
    if (!start_verifier(o, verifier, err, job_count(o), true)) return 2;
    Options as_json = o;
    as_json.report.format = Format::json;
    std::ostringstream json;
    verify_functions(as_json, *configs, verifier, json, err);
    rep.verification = nlohmann::json::parse(json.str()).at("functions");
  }
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  nlohmann::ordered_json data = report_json(rep);
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"report.html", report_html(data)},
                                   {"report.md", report_markdown(data)},
                                   {"report.json", data.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n"}}) {
    fs::path path = fs::path(o.out_dir) / name;
    std::string why = fs::exists(path, ec) ? replace_file(path, read_file(path, SIZE_MAX).text, text) : create_file(path, text);
    if (!why.empty()) throw std::runtime_error(fmt::format("{}: cannot write: {}", path.string(), why));
  }
  out << fmt::format("Wrote {0}/report.html, {0}/report.md and {0}/report.json: {1} file(s), {2} finding(s), {3} marker(s).\n", o.out_dir,
                     rep.files.size(), data["summary"]["findings"].get<size_t>(), rep.markers.size());
  return 0;
}

// How a rule's fixes are labelled: "safe", "unsafe", "safe, unsafe", or "" when it has none.
std::string fix_labels(const RuleInfo& r) {
  std::set<std::string> labels;
  for (const auto& [kind, fix] : r.fixes) labels.insert(fix.value("applicability", "unsafe"));
  return fmt::format("{}", fmt::join(labels, ", "));
}

int list_rules(const Options& o, std::ostream& out) {
  if (o.report.format == Format::json) {
    nlohmann::json rules = nlohmann::json::array();
    for (const RuleInfo& r : all_rules()) {
      std::vector<std::string> langs = language_names(r);
      std::string labels = fix_labels(r);
      rules.push_back({{"id", r.id}, {"name", r.name}, {"severity", severity_name(r.severity)}, {"languages", langs},
                       {"fix", labels.empty() ? nlohmann::json(nullptr) : nlohmann::json(labels)}, {"summary", r.summary},
                       {"scene_dependent", r.scene_dependent}});
    }
    out << json_text(rules, 1) << '\n';
    return 0;
  }
  size_t width = 4;
  for (const RuleInfo& r : all_rules()) width = std::max(width, r.id.size());
  out << fmt::format("{:<{}} {:<8} {:<10} {:<13} {}\n", "RULE", width, "SEVERITY", "LANGUAGES", "FIX", "SUMMARY");
  for (const RuleInfo& r : all_rules()) {
    std::vector<std::string> langs = language_names(r);
    std::string labels = fix_labels(r);
    out << fmt::format("{:<{}} {:<8} {:<10} {:<13} {}\n", r.id, width, severity_name(r.severity), fmt::format("{}", fmt::join(langs, ",")),
                       labels.empty() ? "-" : labels, r.summary);
  }
  out << "\n`lwcport rule ID` prints a rule's page.\n";
  return 0;
}

int show_rule(const Options& o, std::ostream& out) {
  const std::string& id = o.paths.front();
  if (!find_rule(id)) throw UsageError(fmt::format("no rule '{}' (`lwcport rules` lists them)", id), "rule");
  out << rule_page(id);
  return 0;
}

}  // namespace

HostCommand host_command = nullptr;

namespace {

// `lwcport host` from the lwcport program: lwcport-host beside it, its output passed through.
int run_host_program(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  std::error_code ec;
  fs::path program = fs::read_symlink("/proc/self/exe", ec).parent_path() / "lwcport-host";
  if (ec || ::access(program.c_str(), X_OK) != 0)
    throw std::runtime_error(fmt::format("`lwcport host` needs the lwcport-host program beside lwcport ({} is missing: it is built "
                                         "with Clang 19's LibTooling; .ci/setup installs it)", program.string()));
  int pipes[2][2];
  if (::pipe2(pipes[0], O_CLOEXEC) != 0 || ::pipe2(pipes[1], O_CLOEXEC) != 0) throw std::runtime_error(std::strerror(errno));
  std::vector<std::string> argv_text{program.string()};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::strerror(errno));
  if (pid == 0) {
    ::dup2(pipes[0][1], STDOUT_FILENO);
    ::dup2(pipes[1][1], STDERR_FILENO);
    ::execv(argv[0], argv.data());
    _exit(127);
  }
  ::close(pipes[0][1]);
  ::close(pipes[1][1]);
  struct pollfd fds[2] = {{pipes[0][0], POLLIN, 0}, {pipes[1][0], POLLIN, 0}};
  std::ostream* to[2] = {&out, &err};
  for (int open = 2; open > 0;) {
    if (::poll(fds, 2, -1) < 0 && errno != EINTR) break;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      char buffer[65536];
      ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        to[i]->write(buffer, n);
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      ::close(fds[i].fd);
      fds[i].fd = -1;
      --open;
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  err << fmt::format("lwcport: error: {} ended by signal {} ({})\n", program.string(), WTERMSIG(status), strsignal(WTERMSIG(status)));
  return 2;
}

}  // namespace

int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  try {
    Options o = parse_options(args);
    if (o.command == "help") {
      out << usage(o.help_for);
      return 0;
    }
    if (o.command == "version") {
      out << "lwcport " << LWCPORT_VERSION << '\n';
      return 0;
    }
    if (o.command == "lint") return lint(o, out, err);
    if (o.command == "fix") return fix(o, out, err);
    if (o.command == "parse") return parse_only(o, out, err);
    if (o.command == "verify") return verify(o, out, err);
    if (o.command == "lsp") return run_language_server(std::cin, out, {o.log_file});
    if (o.command == "rules") return list_rules(o, out);
    if (o.command == "rule") return show_rule(o, out);
    if (o.command == "report") return report(o, out, err);
    if (o.command == "host") return host_command ? host_command(o, out, err) : run_host_program(args, out, err);
    throw UsageError("unknown command '" + o.command + "'");
  } catch (const UsageError& e) {
    err << usage_error_line(e);
    return 2;
  } catch (const std::exception& e) {
    err << "lwcport: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace lwc
