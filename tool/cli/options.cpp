#include "cli/options.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "rules/rule.h"

namespace lwc {

namespace {

struct CommandInfo {
  const char* name;
  const char* synopsis;  // after `lwcport NAME`
  const char* summary;   // a line or two, for the overview and the command's own help
};

constexpr CommandInfo kCommands[] = {
    {"lint", "[options] [PATHS...]",
     "report world-space hazards and their fixes (folders recurse; default: .;\n"
     "`-` reads standard input)"},
    {"fix", "[options] [PATHS...]",
     "apply the safe fixes in place, then report what remains (`fix -` writes the\n"
     "fixed text of standard input to standard output)"},
    {"verify", "[options] [PATHS...]",
     "run every function with a finding, as written and as each rewrite, on the\n"
     "Vulkan device (lavapipe) against a float64 reference: error and run time;\n"
     "with --shaderlib, every DoubleFloat operation against its published bounds"},
    {"parse", "[options] [PATHS...]",
     "parse only and count syntax errors (the benchmark's baseline); with\n"
     "--verbose, each error's position and the text around it"},
    {"host", "[options] [PATHS...] [-- CLANG ARGS...]",
     "report (and with --fix, fix) C++ host code that rounds world positions and\n"
     "matrices to float before the GPU sees them, parsed with Clang (docs/host.md)"},
    {"rules", "[--format text|json]", "list the rules: id, severity, languages, whether lwcport fixes it, summary"},
    {"rule", "ID", "print a rule's page: what it finds, why, its fixes and examples"},
    {"report", "[options] [PATHS...]",
     "write a migration report (report.html, report.md, report.json): findings by\n"
     "rule, era and folder, the marker ledger, effort, what each scene needs, and\n"
     "with --history the burn-down over the tree's git history"},
    {"lsp", "[--log FILE]",
     "serve editors over the Language Server Protocol (stdio): diagnostics as\n"
     "you type, quick fixes, hover (docs/editors.md)"},
};

using Apply = void (*)(Options&, const std::string&);

// One flag: which commands take it, its value's shape (null for a switch), its help, and what it sets.
struct Flag {
  const char* name;
  const char* alias;
  const char* commands;  // space-separated
  const char* value;
  const char* help;
  Apply apply;
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

const Flag kFlags[] = {
    {"--format", nullptr, "lint fix verify rules host", "FORMAT",
     "text|json|sarif|github (default: text)",
     [](Options& o, const std::string& f) {
       if (f == "text") o.report.format = Format::text;
       else if (f == "json") o.report.format = Format::json;
       else if (f == "sarif" && o.command != "verify" && o.command != "rules") o.report.format = Format::sarif;
       else if (f == "github" && o.command != "verify" && o.command != "rules") o.report.format = Format::github;
       else if (o.command == "verify" || o.command == "rules") throw UsageError("--format must be text or json", o.command);
       else throw UsageError("--format must be text, json, sarif or github", o.command);
     }},
    {"--statistics", nullptr, "lint fix host", nullptr, "per rule: how many findings, and how many a fix covers, instead of each finding",
     [](Options& o, const std::string&) { o.report.statistics = true; }},
    {"--color", nullptr, "lint fix host", "WHEN",
     "auto|always|never: colour text output (default: auto; NO_COLOR, FORCE_COLOR and CLICOLOR_FORCE are honoured under auto)",
     [](Options& o, const std::string& v) {
       if (v != "auto" && v != "always" && v != "never") throw UsageError("--color must be auto, always or never", o.command);
       o.color = v;
     }},
    {"--fail-on", nullptr, "lint fix verify host", "LEVEL",
     "error|warning|note|none: exit 1 when a finding is at least this severe (default: warning)",
     [](Options& o, const std::string& f) {
       Severity s;
       if (f == "none") o.fail_on.reset();
       else if (parse_severity(f, s)) o.fail_on = s;
       else throw UsageError("--fail-on must be error, warning, note or none", o.command);
     }},
    {"--select", nullptr, "lint fix verify report host", "IDS", "run only these rules (comma-separated)",
     [](Options& o, const std::string& v) { o.select = rule_list(v, "--select"); }},
    {"--ignore", nullptr, "lint fix verify report host", "IDS", "skip these rules (comma-separated)",
     [](Options& o, const std::string& v) { o.ignore = rule_list(v, "--ignore"); }},
    {"--lang", nullptr, "lint fix verify parse report", "LANG", "hlsl|glsl: analyse every file as this language",
     [](Options& o, const std::string& v) {
       o.lang = parse_lang(v);
       if (!o.lang) throw UsageError("--lang must be hlsl or glsl", o.command);
     }},
    {"--stdin-filename", nullptr, "lint fix", "NAME",
     "the name standing for standard input (`-`): its language, config and suppressions come from NAME, and findings are reported under it",
     [](Options& o, const std::string& v) { o.stdin_filename = v; }},
    {"--baseline", nullptr, "lint host", "FILE",
     "report only findings not recorded in FILE (the exit code comes from those alone) and list its entries that no longer match",
     [](Options& o, const std::string& v) { o.baseline_file = v; }},
    {"--write-baseline", nullptr, "lint host", "FILE", "record the current findings in FILE (docs/baseline.md) and exit 0",
     [](Options& o, const std::string& v) { o.write_baseline_file = v; }},
    {"--prune-baseline", nullptr, "lint host", nullptr, "with --baseline: rewrite FILE without the entries that no longer match",
     [](Options& o, const std::string&) { o.prune_baseline = true; }},
    {"--add-suppressions", nullptr, "lint", nullptr,
     "write a `// lwcport-ignore: <id>` comment on the line of each current finding (the alternative to a baseline for teams who prefer them in code)",
     [](Options& o, const std::string&) { o.add_suppressions = true; }},
    {"--config", nullptr, "lint fix verify parse report host", "FILE", "use this .lwcport.json for every file instead of the nearest one",
     [](Options& o, const std::string& v) { o.config_file = v; }},
    {"--isolated", nullptr, "lint fix verify parse report host", nullptr, "read no .lwcport.json: the built-in defaults",
     [](Options& o, const std::string&) { o.isolated = true; }},
    {"--jobs", "-j", "lint fix verify parse report host", "N",
     "worker threads (default: all cores)",
     [](Options& o, const std::string& n) {
       char* end = nullptr;
       long v = std::strtol(n.c_str(), &end, 10);
       if (n.empty() || *end || v < 1 || v > 1024) throw UsageError("--jobs must be a number from 1 to 1024", o.command);
       o.jobs = static_cast<unsigned>(v);
     }},
    {"--output", "-o", "lint fix verify host", "FILE", "write the report to FILE instead of standard output",
     [](Options& o, const std::string& v) { o.output = v; }},
    {"--scene", nullptr, "lint fix verify report", "FILE",
     "the scene profile: world extent, view distance, precision (default: Unreal's full world, 2^43 cm, to 1/16 cm)",
     [](Options& o, const std::string& v) { o.scene = load_scene(v); }},
    {"--strategy", nullptr, "lint fix", "NAME",
     "auto|translated|df: rewrite to translated world, DoubleFloat, or per site from the scene profile (default: auto)",
     [](Options& o, const std::string& v) {
       auto s = parse_strategy(v);
       if (!s) throw UsageError("--strategy must be auto, translated or df", o.command);
       o.strategy = *s;
     }},
    {"--explain", nullptr, "lint fix verify", nullptr,
     "print each scene decision with its numbers",
     [](Options& o, const std::string&) { o.report.explain = true; }},
    {"--out", nullptr, "report", "DIR", "where report.html, report.md and report.json go (default: lwcport-report)",
     [](Options& o, const std::string& v) { o.out_dir = v; }},
    {"--history", nullptr, "report", "N", "the counts at each of the last N commits (first parent) of the tree's git history",
     [](Options& o, const std::string& n) {
       char* end = nullptr;
       long v = std::strtol(n.c_str(), &end, 10);
       if (n.empty() || *end || v < 1 || v > 100000) throw UsageError("--history must be a number of commits from 1", o.command);
       o.history = static_cast<int>(v);
     }},
    {"--since", nullptr, "report", "REV", "the counts at each commit after REV (a commit, tag or branch)",
     [](Options& o, const std::string& v) { o.since = v; }},
    {"--host", nullptr, "report", "PATH",
     "analyse the C++ host code at PATH too (lwcport host; repeatable): a host section pairs each host change with the shaders it feeds",
     [](Options& o, const std::string& v) { o.host_paths.push_back(v); }},
    {"--build-dir", "-p", "host report", "DIR", "the build folder holding compile_commands.json (default: found upward from the paths)",
     [](Options& o, const std::string& v) { o.build_dir = v; }},
    {"--fix", nullptr, "host", nullptr, "apply the safe fixes in place (with --unsafe-fixes, the unsafe ones too)",
     [](Options& o, const std::string&) { o.fix_in_place = true; }},
    {"--diff", nullptr, "fix host", nullptr,
     "print a unified diff of the fixes and write nothing (exit 1 when there is something to fix, unless --fail-on none)",
     [](Options& o, const std::string&) { o.diff = true; }},
    {"--unsafe-fixes", nullptr, "fix host", nullptr, "apply the unsafe fixes too",
     [](Options& o, const std::string&) { o.unsafe_fixes = true; }},
    {"--verify", nullptr, "fix report", nullptr,
     "run each fixed file's functions on the Vulkan device against the float64 reference first; apply only the files whose rewrites all pass",
     [](Options& o, const std::string&) { o.verify = true; }},
    {"--check-build", nullptr, "fix", nullptr,
     "compile each file before and after fixing (glslang; Unreal code against its engine era's stub); a fix that breaks a file's build is held back",
     [](Options& o, const std::string&) { o.check_build = true; }},
    {"--force", nullptr, "fix", nullptr,
     "replace a file that has other hard links too (the other names keep the old content; without it such a file is left unchanged, with the reason)",
     [](Options& o, const std::string&) { o.force = true; }},
    {"--shaderlib", nullptr, "verify", nullptr, "check the DoubleFloat library itself against a double-double reference",
     [](Options& o, const std::string&) { o.shaderlib = true; }},
    {"--timeout", nullptr, "verify report", "SECONDS",
     "stop a kernel that runs longer (default: 60); the driver process is restarted and the other functions still run",
     [](Options& o, const std::string& n) {
       char* end = nullptr;
       double v = std::strtod(n.c_str(), &end);
       if (n.empty() || *end || !(v > 0) || v > 86400) throw UsageError("--timeout must be a number of seconds, above 0", o.command);
       o.timeout_seconds = v;
     }},
    {"--verbose", "-v", "parse", nullptr, "each syntax error with the text around it, and each file skipped",
     [](Options& o, const std::string&) { o.verbose = true; }},
    {"--log", nullptr, "lsp", "FILE", "append the server's log to FILE", [](Options& o, const std::string& v) { o.log_file = v; }},
    {"--stdio", nullptr, "lsp", nullptr, "accepted for editors' clients: standard input and output are the only transport",
     [](Options&, const std::string&) {}},
};

// Where a flag means something of its own to one command, its help there.
struct CommandHelp {
  const char* flag;
  const char* command;
  const char* help;
};
constexpr CommandHelp kCommandHelp[] = {
    {"--format", "verify", "text|json (default: text)"},
    {"--format", "rules", "text|json (default: text)"},
    {"--fail-on", "verify", "none: exit 0 even when a rewrite fails or does not compile"},
    {"--jobs", "verify", "functions verified side by side, one driver process each (default: all cores)"},
    {"--explain", "verify", "print each function's inputs: the role each is given (by the world-space model's kind, else its name) and how it is filled"},
    {"--verify", "report", "verify every function with a finding on the Vulkan device and plot its error against its cost"},
};

const char* help_of(const Flag& flag, std::string_view command) {
  for (const CommandHelp& h : kCommandHelp)
    if (flag.name == std::string_view(h.flag) && command == h.command) return h.help;
  return flag.help;
}

bool takes(const Flag& flag, std::string_view command) {
  std::string_view list = flag.commands;
  for (size_t at = 0; at <= list.size();) {
    size_t end = std::min(list.find(' ', at), list.size());
    if (list.substr(at, end - at) == command) return true;
    at = end + 1;
  }
  return false;
}

const CommandInfo* find_command(std::string_view name) {
  for (const CommandInfo& c : kCommands)
    if (name == c.name) return &c;
  return nullptr;
}

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// ` (did you mean --x?)` for a near miss among the names in `names`, else "".
std::string suggestion(std::string_view typed, const std::vector<std::string>& names) {
  std::string best;
  size_t best_distance = 3;
  for (const std::string& n : names)
    if (size_t d = edit_distance(typed, n); d < best_distance) best_distance = d, best = n;
  return best.empty() ? "" : " (did you mean " + best + "?)";
}

std::string see_help(std::string_view command) {
  return command.empty() ? " (see `lwcport --help`)" : fmt::format(" (see `lwcport {} --help`)", command);
}

// Text wrapped to lines of at most 100 columns, continuation lines indented by `indent`.
std::string wrapped(std::string_view text, size_t indent) {
  std::string out, word;
  size_t column = indent;
  auto flush = [&] {
    if (word.empty()) return;
    if (column > indent && column + 1 + word.size() > 100) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (column > indent) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
    word.clear();
  };
  for (char c : text) {
    if (c == ' ' || c == '\n') flush();
    else word += c;
  }
  flush();
  return out;
}

}  // namespace

std::string usage(std::string_view command) {
  const CommandInfo* info = find_command(command);
  if (!info) {
    std::string out = "usage: lwcport <command> [options] [PATHS...]\n\ncommands:\n";
    for (const CommandInfo& c : kCommands) {
      std::string summary = c.summary;
      for (size_t at = 0; (at = summary.find('\n', at)) != std::string::npos; at += 23) summary.replace(at, 1, "\n" + std::string(22, ' '));
      out += fmt::format("  {:<19} {}\n", c.name, summary);
    }
    out += "\n`lwcport <command> --help` lists a command's options; `lwcport --version` prints the version.\n";
    return out;
  }
  std::string out = fmt::format("usage: lwcport {} {}\n\n{}\n", info->name, info->synopsis, info->summary);
  bool any = false;
  for (const Flag& f : kFlags) {
    if (!takes(f, command) || std::string_view(f.name) == "--stdio") continue;
    if (!any) out += "\noptions:\n";
    any = true;
    std::string left = std::string(f.name) + (f.alias ? std::string(", ") + f.alias : "") + (f.value ? std::string(" ") + f.value : "");
    out += fmt::format("  {:<27} {}\n", left, wrapped(help_of(f, command), 30));
  }
  out += fmt::format("  {:<27} {}\n", "--help, -h", "this text");
  return out;
}

Options parse_options(const std::vector<std::string>& args) {
  Options o;
  // The command comes first; flags are read against it (and `--help` before it is the overview).
  size_t first = 0;
  while (first < args.size() && args[first].size() > 1 && args[first][0] == '-') {
    const std::string& a = args[first];
    if (a == "--help" || a == "-h") o.command = "help";
    else if (a == "--version" || a == "-V") o.command = "version";
    else throw UsageError(fmt::format("{} needs a command before it", a));
    ++first;
  }
  if (!o.command.empty()) return o;
  if (first == args.size()) throw UsageError("no command given");
  o.command = args[first];
  if (o.command == "help") {
    if (first + 1 < args.size()) o.help_for = args[first + 1];
    if (!o.help_for.empty() && !find_command(o.help_for)) throw UsageError("no command '" + o.help_for + "'");
    return o;
  }
  if (!find_command(o.command)) {
    std::vector<std::string> names;
    for (const CommandInfo& c : kCommands) names.push_back(c.name);
    throw UsageError(fmt::format("unknown command '{}'{}", o.command, suggestion(o.command, names)));
  }
  bool only_paths = false;  // after `--`, every argument is a path (for host, a compile flag)
  for (size_t i = first + 1; i < args.size(); ++i) {
    std::string a = args[i];
    if (only_paths && o.command == "host") {
      o.clang_args.push_back(a);
      continue;
    }
    if (only_paths || a == "-" || a.empty() || a[0] != '-') {
      o.paths.push_back(a);
      continue;
    }
    if (a == "--") {
      only_paths = true;
      continue;
    }
    if (a == "--help" || a == "-h") {
      o.help_for = o.command;
      o.command = "help";
      return o;
    }
    std::optional<std::string> inline_value;
    if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
      inline_value = a.substr(a.find('=') + 1);
      a = a.substr(0, a.find('='));
    } else if (a.size() > 2 && a[1] != '-') {  // `-j2`, `-pbuild`: a short option with its value attached
      for (const Flag& f : kFlags)
        if (f.alias && f.value && a.compare(0, 2, f.alias) == 0) {
          inline_value = a.substr(2);
          a = a.substr(0, 2);
          break;
        }
    }
    const Flag* flag = nullptr;
    for (const Flag& f : kFlags)
      if (a == f.name || (f.alias && a == f.alias)) flag = &f;
    if (!flag) {
      std::vector<std::string> names;
      for (const Flag& f : kFlags)
        if (takes(f, o.command)) names.push_back(f.name);
      throw UsageError(fmt::format("unknown option {}{}", a, suggestion(a, names)), o.command);
    }
    if (!takes(*flag, o.command))
      throw UsageError(fmt::format("{} is not an option of `lwcport {}`", flag->name, o.command), o.command);
    std::string value;
    if (flag->value) {
      if (inline_value) value = *inline_value;
      else if (i + 1 < args.size()) value = args[++i];
      else throw UsageError(fmt::format("{} needs a value ({})", flag->name, flag->value), o.command);
    } else if (inline_value) {
      throw UsageError(fmt::format("{} takes no value", flag->name), o.command);
    }
    flag->apply(o, value);
  }
  if (o.command == "rule" && o.paths.size() != 1) throw UsageError("`lwcport rule` takes one rule id", o.command);
  if ((o.command == "rules" || o.command == "lsp") && !o.paths.empty())
    throw UsageError(fmt::format("`lwcport {}` takes no paths", o.command), o.command);
  if (o.report.statistics && (o.report.format == Format::sarif || o.report.format == Format::github))
    throw UsageError("--statistics prints text or json", o.command);
  if (o.fix_in_place && o.diff) throw UsageError("--fix writes the fixes and --diff prints them: use one", o.command);
  if (o.report.statistics && o.diff) throw UsageError("--statistics and --diff cannot be used together", o.command);
  if (o.history && !o.since.empty()) throw UsageError("--history and --since cannot be used together", o.command);
  if (o.prune_baseline && o.baseline_file.empty()) throw UsageError("--prune-baseline needs --baseline FILE", o.command);
  if (int modes = !o.baseline_file.empty() + !o.write_baseline_file.empty() + o.add_suppressions; modes > 1)
    throw UsageError("--baseline, --write-baseline and --add-suppressions are separate ways to adopt lwcport: use one", o.command);
  if (o.add_suppressions && !o.paths.empty() && o.paths[0] == "-")
    throw UsageError("--add-suppressions writes into files; standard input has none", o.command);
  if (o.config_file.size() && o.isolated) throw UsageError("--config and --isolated cannot be used together", o.command);
  size_t from_stdin = std::count(o.paths.begin(), o.paths.end(), "-");
  if (from_stdin && o.command != "lint" && o.command != "fix")
    throw UsageError(fmt::format("`lwcport {}` cannot read standard input; name the files", o.command), o.command);
  if (from_stdin && o.paths.size() > 1) throw UsageError("`-` (standard input) cannot be mixed with other paths", o.command);
  if (!o.stdin_filename.empty() && !from_stdin) throw UsageError("--stdin-filename is for `-` (standard input)", o.command);
  return o;
}

std::string usage_error_line(const UsageError& e) { return fmt::format("lwcport: error: {}{}\n", e.what(), see_help(e.command)); }

}  // namespace lwc
