#include "cli/commands.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "cli/config.h"
#include "cli/files.h"
#include "cli/includes.h"
#include "cli/report.h"
#include "rules/analyze.h"
#include "rules/rule.h"

namespace fs = std::filesystem;

namespace lwc {

namespace {

constexpr const char* kUsage = R"(usage: lwcport <command> [options] [PATHS...]

commands:
  lint [PATHS...]     report world-space hazards (folders recurse; default: .)
  parse [PATHS...]    parse only and count syntax errors (the benchmark's baseline)
  rules               list the rules

lint options:
  --format text|json|sarif|github   output format (default: text)
  --color auto|always|never         colour text output (default: auto)
  --fail-on error|warning|note|none exit 1 when a finding is at least this severe (default: warning)
  --select ID[,ID...]               run only these rules
  --ignore ID[,ID...]               skip these rules
  --lang hlsl|glsl                  analyse every file as this language
  --jobs N                          worker threads (default: all cores)
  --output FILE                     write the report to FILE instead of standard output
  --version, --help
)";

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string command;
  std::vector<std::string> paths;
  ReportOptions report;
  std::string color = "auto";
  std::optional<Severity> fail_on = Severity::warning;
  std::set<std::string> select, ignore;
  std::optional<Lang> lang;
  unsigned jobs = 0;
  std::string output;
};

std::set<std::string> rule_list(const std::string& value, const char* flag) {
  std::set<std::string> out;
  std::stringstream ss(value);
  std::string id;
  while (std::getline(ss, id, ',')) {
    if (id.empty()) continue;
    if (!find_rule(id)) throw UsageError(fmt::format("{}: unknown rule id '{}' (see `lwcport rules`)", flag, id));
    out.insert(id);
  }
  return out;
}

Options parse_options(const std::vector<std::string>& args) {
  Options o;
  size_t i = 0;
  auto value = [&](const std::string& flag) -> std::string {
    if (i + 1 >= args.size()) throw UsageError(flag + " needs a value");
    return args[++i];
  };
  for (; i < args.size(); ++i) {
    std::string a = args[i];
    std::string inline_value;
    if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
      inline_value = a.substr(a.find('=') + 1);
      a = a.substr(0, a.find('='));
    }
    auto get = [&]() { return inline_value.empty() ? value(a) : inline_value; };
    if (a == "--help" || a == "-h") o.command = "help";
    else if (a == "--version") o.command = "version";
    else if (a == "--format") {
      std::string f = get();
      if (f == "text") o.report.format = Format::text;
      else if (f == "json") o.report.format = Format::json;
      else if (f == "sarif") o.report.format = Format::sarif;
      else if (f == "github") o.report.format = Format::github;
      else throw UsageError("--format must be text, json, sarif or github");
    } else if (a == "--color") {
      o.color = get();
      if (o.color != "auto" && o.color != "always" && o.color != "never") throw UsageError("--color must be auto, always or never");
    } else if (a == "--fail-on") {
      std::string f = get();
      Severity s;
      if (f == "none") o.fail_on.reset();
      else if (parse_severity(f, s)) o.fail_on = s;
      else throw UsageError("--fail-on must be error, warning, note or none");
    } else if (a == "--select") o.select = rule_list(get(), "--select");
    else if (a == "--ignore") o.ignore = rule_list(get(), "--ignore");
    else if (a == "--lang") {
      o.lang = parse_lang(get());
      if (!o.lang) throw UsageError("--lang must be hlsl or glsl");
    } else if (a == "--jobs" || a == "-j") {
      std::string n = get();
      char* end = nullptr;
      long v = std::strtol(n.c_str(), &end, 10);
      if (*end || v < 1 || v > 1024) throw UsageError("--jobs must be a number from 1 to 1024");
      o.jobs = static_cast<unsigned>(v);
    } else if (a == "--output" || a == "-o") o.output = get();
    else if (a.size() > 1 && a[0] == '-') throw UsageError("unknown option " + a);
    else if (o.command.empty()) o.command = a;
    else o.paths.push_back(a);
  }
  if (o.command.empty()) throw UsageError("no command given");
  return o;
}

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

FileReport lint_file(const InputFile& file, const Options& o, IncludeSummaries& includes) {
  FileReport report{file.display, {}};
  const ProjectConfig& config = *file.config;
  auto input_problem = [&](Finding f) {
    Source empty(file.display, "");
    report.findings.push_back(locate(empty, f));
  };
  if (!file.error.empty()) {
    input_problem(input_finding(Severity::error, 0, "cannot read: " + file.error, "check the path and its permissions"));
    return report;
  }
  ReadResult r = read_file(file.path, config.max_file_bytes);
  if (!r.error.empty()) {
    input_problem(input_finding(Severity::error, 0, "cannot read: " + r.error, "check the path and its permissions"));
    return report;
  }
  if (r.too_large) {
    input_problem(too_large_finding(r.size, config.max_file_bytes));
    return report;
  }
  AnalyzeOptions a;
  a.lang = o.lang;
  a.select = o.select;
  a.ignore = o.ignore;
  if (a.select.empty()) a.select.insert(config.select.begin(), config.select.end());
  a.ignore.insert(config.ignore.begin(), config.ignore.end());
  a.severity = config.severity;
  a.world_sources = config.world_sources;
  a.max_bytes = config.max_file_bytes;
  Source source(file.display, std::move(r.text));
  FileSummary summary;
  if (source.text().find("include") != std::string::npos) {
    summary = includes.for_file(file.path, source.text(), config);
    a.includes = &summary;
  }
  for (const Finding& f : analyze(source, a)) report.findings.push_back(locate(source, f));
  return report;
}

int lint(const Options& o, std::ostream& out, std::ostream& err) {
  ConfigFinder configs;
  std::vector<std::string> paths = o.paths.empty() ? std::vector<std::string>{"."} : o.paths;
  std::vector<InputFile> files = discover(paths, configs);

  ReportOptions ro = o.report;
  bool tty = o.output.empty() && ::isatty(STDOUT_FILENO) && !std::getenv("NO_COLOR");
  ro.color = o.color == "always" || (o.color == "auto" && tty);
  ro.working_dir = fs::current_path().string();
  std::ofstream file_out;
  if (!o.output.empty()) {
    file_out.open(o.output, std::ios::binary);
    if (!file_out) {
      err << fmt::format("lwcport: error: cannot write {}\n", o.output);
      return 2;
    }
  }
  ReportWriter writer(o.output.empty() ? out : file_out, ro);

  // Workers fill slots; this thread writes them in path order as soon as each is ready and
  // frees it, so memory holds only the files in flight, not the whole run's findings.
  std::vector<std::optional<FileReport>> slots(files.size());
  std::mutex mutex;
  std::condition_variable ready;
  std::atomic<size_t> next{0};
  IncludeSummaries includes;
  unsigned jobs = o.jobs ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < std::min<size_t>(jobs, files.size()); ++t) {
    workers.emplace_back([&]() {
      for (size_t i; (i = next.fetch_add(1)) < files.size();) {
        FileReport report = lint_file(files[i], o, includes);
        std::lock_guard lock(mutex);
        slots[i] = std::move(report);
        ready.notify_all();
      }
    });
  }
  for (size_t i = 0; i < files.size(); ++i) {
    std::unique_lock lock(mutex);
    ready.wait(lock, [&] { return slots[i].has_value(); });
    FileReport report = std::move(*slots[i]);
    slots[i].reset();
    lock.unlock();
    writer.file(report);
  }
  for (auto& w : workers) w.join();
  writer.finish();
  return o.fail_on && writer.failed(*o.fail_on) ? 1 : 0;
}

int parse_only(const Options& o, std::ostream& out) {
  ConfigFinder configs;
  std::vector<std::string> paths = o.paths.empty() ? std::vector<std::string>{"."} : o.paths;
  std::vector<InputFile> files = discover(paths, configs);
  std::vector<int> errors(files.size());
  std::atomic<size_t> bytes{0};
  unsigned jobs = o.jobs ? o.jobs : std::max(1u, std::thread::hardware_concurrency());
  parallel_for(files.size(), jobs, [&](size_t i) {
    ReadResult r = read_file(files[i].path, files[i].config->max_file_bytes);
    auto lang = o.lang ? o.lang : lang_from_path(files[i].display);
    if (!r.error.empty() || r.too_large || !lang) return;
    bytes += r.text.size();
    Source src(files[i].display, std::move(r.text));
    errors[i] = parse(src, *lang).error_count;
  });
  size_t with_errors = 0;
  for (size_t i = 0; i < files.size(); ++i)
    if (errors[i]) {
      ++with_errors;
      out << fmt::format("{}: {} syntax error node(s)\n", files[i].display, errors[i]);
    }
  out << fmt::format("Parsed {} file(s), {} bytes; {} with syntax errors.\n", files.size(), bytes.load(), with_errors);
  return with_errors ? 1 : 0;
}

void list_rules(std::ostream& out) {
  for (const RuleInfo& r : all_rules()) {
    std::string langs;
    for (Lang l : r.languages) langs += (langs.empty() ? "" : ",") + std::string(lang_name(l));
    out << fmt::format("{:<26} {:<8} {:<10} {}\n", r.id, severity_name(r.severity), langs, r.summary);
  }
}

}  // namespace

int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  try {
    Options o = parse_options(args);
    if (o.command == "help") {
      out << kUsage;
      return 0;
    }
    if (o.command == "version") {
      out << "lwcport " << LWCPORT_VERSION << '\n';
      return 0;
    }
    if (o.command == "lint") return lint(o, out, err);
    if (o.command == "parse") return parse_only(o, out);
    if (o.command == "rules") {
      list_rules(out);
      return 0;
    }
    throw UsageError("unknown command '" + o.command + "'");
  } catch (const UsageError& e) {
    err << "lwcport: error: " << e.what() << "\n\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {
    err << "lwcport: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace lwc
