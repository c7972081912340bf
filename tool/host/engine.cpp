// Drives Clang over the translation units: compile commands, one parse per unit on a pool of
// threads, the checks' matchers, and the findings gathered per file.
#include <clang/Basic/Diagnostic.h>
#include <clang/Frontend/CompilerInstance.h>
#include <clang/Frontend/FrontendAction.h>
#include <clang/Lex/Lexer.h>
#include <clang/Lex/Preprocessor.h>
#include <clang/Tooling/ArgumentsAdjusters.h>
#include <clang/Tooling/CompilationDatabase.h>
#include <clang/Tooling/JSONCompilationDatabase.h>
#include <clang/Tooling/Tooling.h>
#include <fmt/format.h>

#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>
#include <tuple>

#include "host/check.h"
#include "host/checks/narrowing.h"
#include "host/isolate.h"
#include "host/host.h"
#include "host/member_values.h"
#include "host/unit_result.h"
#include "project/files.h"
#include "rules/analyze.h"

namespace lwc {

namespace fs = std::filesystem;
using namespace clang;

bool HostOptions::enabled(const std::string& rule) const {
  return (select.empty() || select.count(rule)) && !ignore.count(rule);
}

namespace host {

Finding* Reporter::report(const RuleInfo& rule, const SourceManager& sm, const LangOptions& lang, SourceRange range, const Vars& vars,
                          const std::string& rests_on) {
  auto at = place(sm, lang, CharSourceRange::getTokenRange(range));
  if (!at) return nullptr;
  File& file = files_[at->first];
  file.rests_on.push_back(rests_on);
  file.findings.push_back(make_finding(rule, at->second, vars));
  return &file.findings.back();
}

Fix* Reporter::fix(Finding& finding, const RuleInfo& rule, std::string_view kind, const Vars& vars, const std::vector<Change>& changes,
                   const SourceManager& sm, const LangOptions& lang) {
  // The finding's own file; an edit elsewhere (a member declared in a header) names its file.
  std::string own;
  for (const auto& [path, file] : files_)
    if (!file.findings.empty() && &finding >= &file.findings.front() && &finding <= &file.findings.back()) own = path;
  std::vector<Edit> edits;
  for (const Change& c : changes) {
    auto at = place(sm, lang, c.range);
    if (!at) return nullptr;  // outside the files this run reports on (a system or third-party header)
    edits.push_back({at->second, c.text, at->first == own ? "" : at->first});
  }
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return std::tie(a.path, a.span.begin) < std::tie(b.path, b.span.begin); });
  finding.fixes.push_back(make_fix(rule, kind, vars, std::move(edits)));
  return &finding.fixes.back();
}

void Reporter::comment(const SourceManager& sm, SourceRange range) {
  FileID id = sm.getFileID(range.getBegin());
  if (!range.getBegin().isFileID() || !file_of(sm, id)) return;
  files_[paths_[id.getHashValue()]].comments.push_back(
      {sm.getFileOffset(range.getBegin()), sm.getFileOffset(range.getEnd())});
}

// A file's absolute path as Clang opened it (relative names are relative to the command's folder,
// which is not this process's working directory).
static std::string real_path(FileEntryRef entry) {
  StringRef real = entry.getFileEntry().tryGetRealPathName();
  return real.empty() ? fs::absolute(entry.getName().str()).string() : real.str();
}

Reporter::File* Reporter::file_of(const SourceManager& sm, FileID id) {
  auto [it, fresh] = paths_.emplace(id.getHashValue(), "");
  if (fresh) {
    OptionalFileEntryRef entry = sm.getFileEntryRefForID(id);
    if (entry && !sm.isInSystemHeader(sm.getLocForStartOfFile(id))) {
      std::error_code ec;
      fs::path path = fs::weakly_canonical(real_path(*entry), ec);
      if (!ec && reported_(path.string())) {
        it->second = path.string();
        File& file = files_[it->second];
        if (file.text.empty()) file.text = sm.getBufferData(id).str();
      }
    }
  }
  return it->second.empty() ? nullptr : &files_[it->second];
}

std::optional<std::pair<std::string, Span>> Reporter::place(const SourceManager& sm, const LangOptions& lang, CharSourceRange range) {
  // Code a macro wrote is reported where the macro is used.
  if (range.getBegin().isMacroID() || range.getEnd().isMacroID()) {
    CharSourceRange file_range = Lexer::makeFileCharRange(range, sm, lang);
    if (file_range.isInvalid()) {
      SourceLocation at = sm.getExpansionLoc(range.getBegin());
      file_range = CharSourceRange::getCharRange(at, Lexer::getLocForEndOfToken(at, 0, sm, lang));
    }
    range = file_range;
  } else if (range.isTokenRange()) {
    range = CharSourceRange::getCharRange(range.getBegin(), Lexer::getLocForEndOfToken(range.getEnd(), 0, sm, lang));
  }
  if (range.isInvalid()) return std::nullopt;
  FileID id = sm.getFileID(range.getBegin());
  if (id != sm.getFileID(range.getEnd()) || !file_of(sm, id)) return std::nullopt;
  unsigned begin = sm.getFileOffset(range.getBegin()), end = sm.getFileOffset(range.getEnd());
  if (end < begin) return std::nullopt;
  return std::make_pair(paths_[id.getHashValue()], Span{begin, end});
}

namespace {

bool is_source(const fs::path& p) {
  static const std::set<std::string> kSources = {".cpp", ".cc", ".cxx", ".c++", ".C", ".mm", ".m"};
  return kSources.count(p.extension().string()) > 0;
}

bool under(const std::string& path, const std::string& folder) {
  return path.size() > folder.size() && path.compare(0, folder.size(), folder) == 0 && (folder.back() == '/' || path[folder.size()] == '/');
}

std::string shown(const std::string& absolute, const fs::path& cwd) {
  if (under(absolute, cwd.string())) return fs::path(absolute).lexically_relative(cwd).string();
  return absolute;
}

// Keeps Clang's diagnostics: the first error of a unit becomes that file's input finding.
class Diagnostics : public DiagnosticConsumer {
 public:
  // `cwd`: where lwcport runs (Clang works in each command's directory meanwhile).
  explicit Diagnostics(fs::path cwd) : cwd_(std::move(cwd)) {}
  void HandleDiagnostic(DiagnosticsEngine::Level level, const Diagnostic& info) override {
    DiagnosticConsumer::HandleDiagnostic(level, info);
    if (level < DiagnosticsEngine::Error || !first.empty()) return;
    llvm::SmallString<200> message;
    info.FormatDiagnostic(message);
    first = message.str().str();
    if (info.hasSourceManager() && info.getLocation().isValid()) {
      const SourceManager& sm = info.getSourceManager();
      PresumedLoc at = sm.getPresumedLoc(info.getLocation());
      if (at.isValid()) {
        OptionalFileEntryRef entry = sm.getFileEntryRefForID(sm.getFileID(sm.getExpansionLoc(info.getLocation())));
        std::string file = entry ? real_path(*entry) : at.getFilename();
        first = fmt::format("{}:{}:{}: {}", shown(fs::path(file).lexically_normal().string(), cwd_), at.getLine(), at.getColumn(), first);
      }
    }
  }
  std::string first;

 private:
  fs::path cwd_;
};

// The arguments every unit is compiled with, on top of its own command.
void adjust_arguments(tooling::ClangTool& tool, std::vector<std::string>& notes) {
  using tooling::ArgumentInsertPosition;
  // CMake's precompiled header (`-Xclang -include-pch -Xclang X.pch`) is a file the build makes, in
  // the format of the compiler that made it: the header it was made from is read instead.
  tool.appendArgumentsAdjuster([&notes](const tooling::CommandLineArguments& args, StringRef) {
    tooling::CommandLineArguments kept;
    std::string pch;
    std::set<std::string> included;
    for (size_t k = 0; k < args.size(); ++k) {
      bool wrapped = args[k] == "-Xclang" && k + 3 < args.size() && args[k + 1] == "-include-pch" && args[k + 2] == "-Xclang";
      if (wrapped || (args[k] == "-include-pch" && k + 1 < args.size())) {
        pch = args[wrapped ? k + 3 : k + 1];
        k += wrapped ? 3 : 1;
        continue;
      }
      if (args[k] == "-include" && k + 1 < args.size()) included.insert(args[k + 1] == "-Xclang" && k + 2 < args.size() ? args[k + 2] : args[k + 1]);
      kept.push_back(args[k]);
    }
    if (pch.empty()) return kept;
    std::string header = pch;
    for (const char* ext : {".pch", ".gch"})
      if (StringRef(header).ends_with(ext)) header.resize(header.size() - 4);
    if (included.count(header)) {
      notes.push_back(fmt::format("the precompiled header {} is not read: the header it was made from is, as the unit's command includes it", pch));
    } else if (header != pch && llvm::sys::fs::exists(header)) {
      kept.insert(kept.begin() + 1, {"-include", header});  // after the compiler's name
      notes.push_back(fmt::format("the precompiled header {} is not read: {}, which it was made from, is included in its place", pch, header));
    } else {
      notes.push_back(fmt::format("the precompiled header {} is not read, and no header it was made from was found: units that rely on it may not compile", pch));
    }
    return kept;
  });
  tool.appendArgumentsAdjuster(tooling::getInsertArgumentAdjuster("-resource-dir=" LWCPORT_CLANG_RESOURCE_DIR, ArgumentInsertPosition::END));
  // Our finding reports a unit's first error: no caret diagnostics, no "N errors generated", no
  // "Error while processing".
  tool.appendArgumentsAdjuster(tooling::getInsertArgumentAdjuster("-fno-caret-diagnostics", ArgumentInsertPosition::END));
  // Compiler warnings are not our findings, and a project's -Werror must not turn one that this
  // Clang gives (and the project's own compiler may not) into a unit we cannot read.
  tool.appendArgumentsAdjuster(tooling::getInsertArgumentAdjuster("-w", ArgumentInsertPosition::END));
  // Nor may what Clang 19 makes an error by default where GCC, and the Clang a project was written
  // for, only warn (docs/host.md lists them): `register` in C++17 (osgEarth's bundled libraries),
  // an enumeration given a value outside its range in a constant (Boost 1.74's MPL), and C's
  // implicit declarations, implicit int and pointer conversions.
  for (const char* flag : {"-Wno-register", "-Wno-enum-constexpr-conversion", "-Wno-error=implicit-function-declaration", "-Wno-error=implicit-int",
                           "-Wno-error=int-conversion", "-Wno-error=incompatible-function-pointer-types"})
    tool.appendArgumentsAdjuster(tooling::getInsertArgumentAdjuster(flag, ArgumentInsertPosition::END));
}

class CommentCollector : public CommentHandler {
 public:
  explicit CommentCollector(Reporter& out) : out_(out) {}
  bool HandleComment(Preprocessor& pp, SourceRange range) override {
    out_.comment(pp.getSourceManager(), range);
    return false;
  }

 private:
  Reporter& out_;
};

// Runs the matchers over the declarations of the files findings are reported in only: the
// standard library, system and other headers are parsed but not walked (a walk of everything
// cost as much again as the checks themselves).
class ProjectMatcher : public ASTConsumer {
 public:
  ProjectMatcher(ast_matchers::MatchFinder& finder, Reporter& out) : finder_(finder), out_(out) {}
  void HandleTranslationUnit(ASTContext& context) override {
    const SourceManager& sm = context.getSourceManager();
    std::vector<Decl*> scope;
    for (Decl* d : context.getTranslationUnitDecl()->decls()) {
      SourceLocation at = sm.getExpansionLoc(d->getLocation());
      if (at.isValid() && out_.reports(sm, sm.getFileID(at))) scope.push_back(d);
    }
    context.setTraversalScope(scope);
    finder_.matchAST(context);
  }

 private:
  ast_matchers::MatchFinder& finder_;
  Reporter& out_;
};

class Action : public ASTFrontendAction {
 public:
  Action(ast_matchers::MatchFinder& finder, Reporter& out) : finder_(finder), out_(out), comments_(out) {}
  std::unique_ptr<ASTConsumer> CreateASTConsumer(CompilerInstance& ci, StringRef) override {
    ci.getPreprocessor().addCommentHandler(&comments_);
    return std::make_unique<ProjectMatcher>(finder_, out_);
  }

 private:
  ast_matchers::MatchFinder& finder_;
  Reporter& out_;
  CommentCollector comments_;
};

class ActionFactory : public tooling::FrontendActionFactory {
 public:
  ActionFactory(ast_matchers::MatchFinder& finder, Reporter& out) : finder_(finder), out_(out) {}
  std::unique_ptr<FrontendAction> create() override { return std::make_unique<Action>(finder_, out_); }

 private:
  ast_matchers::MatchFinder& finder_;
  Reporter& out_;
};

// The compile_commands.json of `folder`, each relative `directory` resolved against the folder
// (as Clang's tools resolve it: a database written with "." beside it, or "../src" from a build
// folder), else the folder's database as Clang loads it; null and `error` when there is none.
std::unique_ptr<tooling::CompilationDatabase> load_database(const fs::path& folder, std::string& error) {
  std::error_code ec;
  fs::path file = folder / "compile_commands.json";
  ReadResult r = fs::is_regular_file(file, ec) ? read_file(file, 1u << 30) : ReadResult{};
  nlohmann::json entries = r.error.empty() ? nlohmann::json::parse(r.text, nullptr, false) : nlohmann::json();
  bool relative = false;
  if (entries.is_array()) {
    fs::path base = fs::absolute(folder, ec).lexically_normal();
    for (auto& e : entries)
      if (e.is_object() && e.contains("directory") && e.at("directory").is_string() && fs::path(e.at("directory").get<std::string>()).is_relative()) {
        e["directory"] = (base / e.at("directory").get<std::string>()).lexically_normal().string();
        relative = true;
      }
  }
  if (!relative) return tooling::CompilationDatabase::loadFromDirectory(folder.string(), error);
  return tooling::JSONCompilationDatabase::loadFromBuffer(entries.dump(), error, tooling::JSONCommandLineSyntax::AutoDetect);
}

// The database Clang's tools would find for a unit in `folder`: the nearest compile_commands.json
// upward (load_database), else what Clang detects there (compile_flags.txt), or null.
std::unique_ptr<tooling::CompilationDatabase> detect_database(const fs::path& folder, std::string& error) {
  std::error_code ec;
  for (fs::path at = fs::absolute(folder, ec); !at.empty(); at = at.parent_path()) {
    if (fs::is_regular_file(at / "compile_commands.json", ec)) return load_database(at, error);
    if (at == at.parent_path()) break;
  }
  return tooling::CompilationDatabase::autoDetectFromDirectory(folder.string(), error);
}

}  // namespace
}  // namespace host

HostResult analyze_host(const HostOptions& options) {
  HostResult result;
  std::error_code ec;
  fs::path cwd = fs::current_path(ec);
  std::string error;
  // The compile commands: the database -p names, or the flags after `--`, for every unit; else each
  // unit's own compile_commands.json or compile_flags.txt, found upward from it (as Clang's tools
  // do), and plain C++20 where there is none. A file a database does not list gets the command of
  // its nearest neighbour.
  std::unique_ptr<tooling::CompilationDatabase> given;
  if (!options.build_dir.empty()) {
    given = host::load_database(options.build_dir, error);
    if (!given) {
      result.errors.push_back(fmt::format("{}: no compile_commands.json here ({})", options.build_dir, error));
      return result;
    }
  } else if (!options.clang_args.empty()) {
    given = std::make_unique<tooling::FixedCompilationDatabase>(".", options.clang_args);
  }
  if (given) given = tooling::inferMissingCompileCommands(std::move(given));
  std::map<std::string, std::unique_ptr<tooling::CompilationDatabase>> found;  // by the unit's folder
  auto database_for = [&](const std::string& source) -> tooling::CompilationDatabase& {
    if (given) return *given;
    std::string folder = fs::path(source).parent_path().string();
    auto [it, fresh] = found.emplace(folder, nullptr);
    if (fresh) {
      std::string why;
      it->second = host::detect_database(folder, why);
      if (!it->second) it->second = std::make_unique<tooling::FixedCompilationDatabase>(".", std::vector<std::string>{"-std=c++20"});
      it->second = tooling::inferMissingCompileCommands(std::move(it->second));
    }
    return *it->second;
  };

  // The sources: files as named; folders give the database's files under them, else their C++ sources.
  std::vector<std::string> sources;
  std::vector<std::string> roots;  // folders whose headers are reported
  std::set<std::string> seen;
  auto add = [&](const fs::path& p) {
    std::string abs = fs::weakly_canonical(fs::absolute(p), ec).string();
    if (seen.insert(abs).second) sources.push_back(abs);
  };
  std::vector<std::string> listed = given ? given->getAllFiles() : std::vector<std::string>{};
  for (const std::string& p : options.paths.empty() ? std::vector<std::string>{"."} : options.paths) {
    if (!fs::exists(p, ec)) {
      result.errors.push_back(fmt::format("{}: no such file or folder", p));
      continue;
    }
    if (!fs::is_directory(p, ec)) {
      add(p);
      continue;
    }
    std::string folder = fs::weakly_canonical(fs::absolute(p), ec).string();
    roots.push_back(folder);
    size_t before = sources.size();
    for (const std::string& f : listed)
      if (host::under(fs::weakly_canonical(f, ec).string(), folder)) add(f);
    if (sources.size() == before)
      for (auto it = fs::recursive_directory_iterator(p, fs::directory_options::skip_permission_denied, ec); !ec && it != fs::recursive_directory_iterator();
           it.increment(ec))
        if (it->is_regular_file(ec) && host::is_source(it->path())) add(it->path());
  }
  std::sort(sources.begin(), sources.end());
  std::vector<tooling::CompilationDatabase*> databases;  // per unit, found before the threads start
  for (const std::string& source : sources) databases.push_back(&database_for(source));
  if (!cwd.empty()) roots.push_back(cwd.string());
  auto reported = [&, sources_set = std::set<std::string>(sources.begin(), sources.end())](const std::string& path) {
    if (sources_set.count(path)) return true;
    return std::any_of(roots.begin(), roots.end(), [&](const std::string& r) { return host::under(path, r); });
  };

  host::Tables tables = host::Tables::load(options.tables);
  // One unit, in a worker process (isolate.h): what it gives the run, as bytes.
  auto analyze_unit = [&](size_t i) {
    host::Reporter out(reported);
    for (const tooling::CompileCommand& c : databases[i]->getCompileCommands(sources[i])) out.command = c.CommandLine;
    std::vector<std::unique_ptr<host::Check>> checks;
    ast_matchers::MatchFinder finder;
    host::NarrowingFan narrowings(tables);  // the checks that read uploads share one set of matchers
    for (const RuleInfo& rule : all_rules()) {
      auto factory = host::check_factories().find(rule.id);
      if (!rule.host || !options.enabled(rule.id) || factory == host::check_factories().end()) continue;
      checks.push_back(factory->second(rule, tables, out));
      checks.back()->register_matchers(finder);
      if (auto* reads_uploads = dynamic_cast<host::UploadCheck*>(checks.back().get())) narrowings.checks.push_back(reads_uploads);
    }
    host::MemberValueCollector given(tables);
    if (!narrowings.checks.empty()) {
      host::register_narrowings(finder, &narrowings, tables);
      given.register_matchers(finder);
    }
    // A file system of its own, with its own working directory: Clang works in each command's folder.
    tooling::ClangTool tool(*databases[i], {sources[i]}, std::make_shared<PCHContainerOperations>(), llvm::vfs::createPhysicalFileSystem());
    host::UnitResult unit;
    host::adjust_arguments(tool, unit.notes);
    tool.setPrintErrorMessage(false);
    host::Diagnostics diagnostics(cwd);
    tool.setDiagnosticConsumer(&diagnostics);
    host::ActionFactory factory(finder, out);
    int status = tool.run(&factory);
    if (status != 0 || !diagnostics.first.empty()) unit.error = diagnostics.first.empty() ? "no compile command" : diagnostics.first;
    unit.given = std::move(given.values);
    std::set<std::string> edited;  // other files a fix edits: their text is needed to place the edits
    for (auto& [path, f] : out.files())
      for (const Finding& finding : f.findings)
        for (const Fix& fix : finding.fixes)
          for (const Edit& e : fix.edits) edited.insert(e.path);
    for (auto& [path, f] : out.files()) {
      HostFile& into = unit.files[path];
      // Only what the run reads comes back: the comments that may suppress, and the text of a file
      // with findings or such comments (a unit's hundred headers are otherwise just counted).
      for (const Span& c : f.comments)
        if (std::string_view(f.text).substr(c.begin, c.end - c.begin).find(kSuppressionMarker) != std::string_view::npos) into.comments.push_back(c);
      if (!f.findings.empty() || !into.comments.empty() || edited.count(path)) into.text = std::move(f.text);
      for (size_t k = 0; k < f.findings.size(); ++k) {
        if (f.rests_on[k].empty()) into.findings.push_back(std::move(f.findings[k]));
        else unit.resting.push_back({path, std::move(f.findings[k]), f.rests_on[k]});
      }
    }
    return host::to_bytes(unit);
  };

  std::map<std::string, HostFile> files;
  // Findings that rest on a member's name alone wait for every unit's values for that member.
  host::MemberValues member_values;
  std::vector<host::RestingFinding> resting;
  auto add_finding = [](HostFile& into, Finding&& finding) {
    // A header included by several units: each finding once.
    bool known = std::any_of(into.findings.begin(), into.findings.end(), [&](const Finding& g) {
      return g.rule == finding.rule && g.span == finding.span && g.message == finding.message;
    });
    if (!known) into.findings.push_back(std::move(finding));
  };
  // Every unit's own file is reported on (and counted), findings or not.
  auto unit_file = [&](size_t i) -> HostFile& {
    HostFile& main = files[sources[i]];
    if (main.text.empty()) main.text = read_file(sources[i], SIZE_MAX).text;
    return main;
  };
  auto merge = [&](size_t i, host::UnitResult&& unit) {
    if (!unit.error.empty()) {
      ++result.counts.failed;
      unit_file(i).findings.push_back(input_finding(Severity::error, 0, "Clang could not compile this translation unit: " + unit.error,
                                                    "give its compile flags: -p BUILD_DIR (compile_commands.json) or after `--`; "
                                                    "findings in the code Clang could read are still reported"));
    } else {
      ++result.counts.analysed;
    }
    for (std::string& note : unit.notes) result.notes.insert(std::move(note));
    for (auto& [key, counts] : unit.given) {
      host::GivenValues& all = member_values[key];
      all.world += counts.world, all.not_world += counts.not_world;
    }
    for (auto& [path, f] : unit.files) {
      HostFile& into = files[path];
      if (into.text.empty()) into.text = std::move(f.text);
      for (Finding& finding : f.findings) add_finding(into, std::move(finding));
      if (into.comments.empty()) into.comments = std::move(f.comments);
    }
    unit_file(i);
    std::move(unit.resting.begin(), unit.resting.end(), std::back_inserter(resting));
  };
  auto stopped = [&](size_t i, const std::string& why) {
    ++result.counts.crashed;
    unit_file(i).findings.push_back(input_finding(Severity::error, 0, "lwcport could not analyse this translation unit: " + why +
                                                      "; nothing from it is reported, the run's other units are",
                                                  "a bug in lwcport: please report it with this unit's compile command "
                                                  "(`lwcport host` on this file alone shows it again)"));
  };
  // A unit the database lists but the disk does not hold yet (a source the build generates).
  std::vector<size_t> to_run;
  for (size_t i = 0; i < sources.size(); ++i) {
    if (fs::is_regular_file(sources[i], ec)) to_run.push_back(i);
    else result.skipped.push_back(host::shown(sources[i], cwd));
  }
  result.counts.skipped = result.skipped.size();
  auto done = [&](size_t k, std::string&& bytes) {
    host::UnitResult unit;
    try {
      unit = host::from_bytes(bytes);
    } catch (const std::exception&) {
      return stopped(to_run[k], "its results could not be read back");
    }
    merge(to_run[k], std::move(unit));
  };
  if (options.isolate) {
    host::run_isolated(to_run.size(), options.jobs, options.unit_cpu_seconds, [&](size_t k) { return analyze_unit(to_run[k]); }, done,
                       [&](size_t k, const std::string& why) { stopped(to_run[k], why); });
  } else {
    for (size_t k = 0; k < to_run.size(); ++k) done(k, analyze_unit(to_run[k]));
  }
  result.units = to_run.size();
  for (host::RestingFinding& r : resting)
    if (!member_values[r.member].overturn_name()) add_finding(files[r.path], std::move(r.finding));
  if (sources.empty() && result.errors.empty()) result.errors.push_back("no C++ sources to analyse");
  for (auto& [path, f] : files) {
    f.path = host::shown(path, cwd);
    for (Finding& finding : f.findings)
      for (Fix& fix : finding.fixes)
        for (Edit& e : fix.edits)
          if (!e.path.empty()) e.path = host::shown(e.path, cwd);
    sort_findings(f.findings);
    result.files.push_back(std::move(f));
  }
  return result;
}

}  // namespace lwc
