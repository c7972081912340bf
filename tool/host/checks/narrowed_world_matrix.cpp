// lwc-host-narrowed-world-matrix: a matrix with the world translation in it narrowed to float for upload.
#include "host/check.h"
#include "host/checks/high_low.h"
#include "host/checks/narrowing.h"

#include <clang/AST/ExprCXX.h>
#include <clang/Lex/Lexer.h>

namespace lwc::host {

using namespace clang;

namespace {

class NarrowedWorldMatrix : public PortedUploadCheck {
 public:
  using PortedUploadCheck::PortedUploadCheck;

  bool reports(const Upload& up) const override { return up.value.kind == Kind::matrix && up.gpu; }
  const char* port() const override { return "translated-matrix"; }

  // The view's PreViewTranslation folded into the matrix in double; "" when offered, else why not.
  std::string translated(const Upload& up, const CameraInScope& camera, Finding& finding, Vars& vars,
                         const ast_matchers::MatchFinder::MatchResult& match) override {
    const SourceManager& sm = *match.SourceManager;
    const LangOptions& lang = match.Context->getLangOpts();
    if (camera.subtract) return "the camera is given as a world origin, and matrices are moved only with UE's PreViewTranslation";
    vars["preview"] = camera.code;
    // Row vectors: M.ConcatTranslation(T) is M, then a move by T (local to translated world);
    // FTranslationMatrix(-T) * M moves back by T first (translated world to view or clip).
    const Expr* value = strip(up.value_expr);
    bool postfix = isa<DeclRefExpr, MemberExpr, CallExpr, ParenExpr>(value) && !isa<CXXOperatorCallExpr>(value);
    CharSourceRange range = CharSourceRange::getTokenRange(up.value_expr->getSourceRange());
    SourceLocation begin = sm.getExpansionLoc(range.getBegin());
    SourceLocation end = Lexer::getLocForEndOfToken(sm.getExpansionLoc(range.getEnd()), 0, sm, lang);
    std::vector<Reporter::Change> changes;
    if (up.value.from_world) {
      changes.push_back({CharSourceRange::getCharRange(begin, begin), "FTranslationMatrix(-" + camera.code + ") * " + (postfix ? "" : "(")});
      if (!postfix) changes.push_back({CharSourceRange::getCharRange(end, end), ")"});
    } else {
      if (!postfix) changes.push_back({CharSourceRange::getCharRange(begin, begin), "("});
      changes.push_back({CharSourceRange::getCharRange(end, end), (postfix ? "" : ")") + std::string(".ConcatTranslation(") + camera.code + ")"});
    }
    out_.fix(finding, rule_, up.value.from_world ? "translated-from-world" : "translated", vars, changes, sm, lang);
    return "";
  }
};

}  // namespace

std::unique_ptr<Check> make_narrowed_world_matrix(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<NarrowedWorldMatrix>(rule, tables, out);
}

}  // namespace lwc::host
