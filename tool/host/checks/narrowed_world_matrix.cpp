// lwc-host-narrowed-world-matrix: a matrix with the world translation in it narrowed to float for upload.
#include "host/check.h"
#include "host/checks/narrowing.h"

#include <clang/Lex/Lexer.h>

#include <clang/AST/ExprCXX.h>

namespace lwc::host {

using namespace clang;

namespace {

class NarrowedWorldMatrix : public UploadCheck {
 public:
  using UploadCheck::UploadCheck;

  void upload(const Upload& found, const ast_matchers::MatchFinder::MatchResult& match) override {
    if (found.value.kind != Kind::matrix || !found.gpu) return;
    const Upload* up = &found;
    const SourceManager& sm = *match.SourceManager;
    const LangOptions& lang = match.Context->getLangOpts();
    Vars vars;
    std::string preview;
    Finding* finding = report_upload(*up, match, rule_, out_, tables_, "translated-matrix", vars, preview);
    if (!finding || preview.empty()) return;
    // Row vectors: M.ConcatTranslation(T) is M, then a move by T (local to translated world);
    // FTranslationMatrix(-T) * M moves back by T first (translated world to view or clip).
    const Expr* value = strip(up->value_expr);
    bool postfix = isa<DeclRefExpr, MemberExpr, CallExpr, ParenExpr>(value) && !isa<CXXOperatorCallExpr>(value);
    CharSourceRange range = CharSourceRange::getTokenRange(up->value_expr->getSourceRange());
    SourceLocation begin = sm.getExpansionLoc(range.getBegin());
    SourceLocation end = Lexer::getLocForEndOfToken(sm.getExpansionLoc(range.getEnd()), 0, sm, lang);
    std::vector<Reporter::Change> changes;
    if (up->value.from_world) {
      changes.push_back({CharSourceRange::getCharRange(begin, begin), "FTranslationMatrix(-" + preview + ") * " + (postfix ? "" : "(")});
      if (!postfix) changes.push_back({CharSourceRange::getCharRange(end, end), ")"});
    } else {
      if (!postfix) changes.push_back({CharSourceRange::getCharRange(begin, begin), "("});
      changes.push_back({CharSourceRange::getCharRange(end, end), (postfix ? "" : ")") + std::string(".ConcatTranslation(") + preview + ")"});
    }
    out_.fix(*finding, rule_, up->value.from_world ? "translated-from-world" : "translated", vars, changes, sm, lang);
  }
};

}  // namespace

std::unique_ptr<Check> make_narrowed_world_matrix(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<NarrowedWorldMatrix>(rule, tables, out);
}

}  // namespace lwc::host
