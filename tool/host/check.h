#pragma once
#include <map>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <clang/ASTMatchers/ASTMatchFinder.h>

#include "core/finding.h"
#include "host/world.h"
#include "rules/rule.h"

namespace lwc::host {

// Where one translation unit's findings go: each at a byte span of the file it is in (the
// expansion of a macro counts as where the macro is used), only in files the run reports on.
class Reporter {
 public:
  struct File {
    std::string text;
    std::vector<Finding> findings;
    std::vector<std::string> rests_on;  // per finding: the member whose name alone it rests on (member_key), or ""
    std::vector<Span> comments;
  };
  // `reported(path)`: whether findings in that file (absolute) are wanted.
  explicit Reporter(std::function<bool(const std::string&)> reported) : reported_(std::move(reported)) {}

  // The finding of `rule` at `range`, its message and hint filled from vars; null when the range
  // is not in a reported file. `rests_on`: the member whose name alone the finding rests on, which
  // the whole run's values for that member may overturn (member_values.h).
  Finding* report(const RuleInfo& rule, const clang::SourceManager& sm, const clang::LangOptions& lang, clang::SourceRange range,
                  const Vars& vars, const std::string& rests_on = "");
  // Adds a rewrite to a finding: each edit replaces a range (an empty range inserts) in the finding's file.
  struct Change {
    clang::CharSourceRange range;
    std::string text;
  };
  Fix* fix(Finding& finding, const RuleInfo& rule, std::string_view kind, const Vars& vars, const std::vector<Change>& changes,
           const clang::SourceManager& sm, const clang::LangOptions& lang);
  // Records a comment, for the lwcport-ignore comments.
  void comment(const clang::SourceManager& sm, clang::SourceRange range);
  std::map<std::string, File>& files() { return files_; }
  // Whether findings in this file are wanted (not a system header; a unit's file or under the
  // project's folders).
  bool reports(const clang::SourceManager& sm, clang::FileID id) { return file_of(sm, id) != nullptr; }
  // The unit's compile command (its arguments), for checks that read compiler settings.
  std::vector<std::string> command;

 private:
  // The file and byte span of a range, if it is in a reported file.
  std::optional<std::pair<std::string, Span>> place(const clang::SourceManager& sm, const clang::LangOptions& lang,
                                                    clang::CharSourceRange range);
  File* file_of(const clang::SourceManager& sm, clang::FileID id);
  std::function<bool(const std::string&)> reported_;
  std::map<std::string, File> files_;
  std::map<unsigned, std::string> paths_;  // FileID hash -> absolute path ("" when not reported)
};

// The code half of a host rule: AST matchers, and what a match means.
class Check : public clang::ast_matchers::MatchFinder::MatchCallback {
 public:
  Check(const RuleInfo& rule, const Tables& tables, Reporter& out) : rule_(rule), tables_(tables), out_(out) {}
  virtual void register_matchers(clang::ast_matchers::MatchFinder& finder) = 0;

 protected:
  const RuleInfo& rule_;
  const Tables& tables_;
  Reporter& out_;
};

using CheckFactory = std::unique_ptr<Check> (*)(const RuleInfo&, const Tables&, Reporter&);
// Host checks by rule id (checks.cpp registers each one).
const std::map<std::string_view, CheckFactory>& check_factories();

}  // namespace lwc::host
