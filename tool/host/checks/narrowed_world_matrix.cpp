// lwc-host-narrowed-world-matrix: a matrix with the world translation in it narrowed to float for upload.
#include "host/check.h"
#include "host/checks/narrowing.h"

#include <clang/Lex/Lexer.h>

#include <clang/AST/ExprCXX.h>

namespace lwc::host {

using namespace clang;

namespace {

class NarrowedWorldMatrix : public Check {
 public:
  using Check::Check;
  void register_matchers(ast_matchers::MatchFinder&) override {}
  bool reads_narrowings() const override { return true; }

  void run(const ast_matchers::MatchFinder::MatchResult& match) override {
    std::optional<Upload> up = find_upload(match, tables_, Kind::matrix);
    if (!up || !up->gpu) return;
    const SourceManager& sm = *match.SourceManager;
    const LangOptions& lang = match.Context->getLangOpts();
    World world(tables_, *match.Context);
    Vars vars{{"narrowing", world.text(up->narrowing->getSourceRange())}, {"type", up->narrowing_type},
              {"value", up->value.source}, {"sink", up->sink}, {"field", up->field.empty() ? "the uploaded matrix" : "`" + up->field + "`"}};
    Finding* finding = out_.report(rule_, sm, lang, up->narrowing->getSourceRange(), vars);
    if (!finding) return;
    if (!up->field.empty()) finding->facts = {{"shader-parameter", up->field}, {"port", "translated-matrix"}};
    std::string preview = preview_translation(up->narrowing, *match.Context, tables_);
    if (preview.empty()) {
      finding->withheld.push_back("translated: no view in scope (a parameter or local of a view type, rules/host-world.json \"views\")");
      return;
    }
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
    vars["preview"] = preview;
    out_.fix(*finding, rule_, up->value.from_world ? "translated-from-world" : "translated", vars, changes, sm, lang);
  }
};

}  // namespace

std::unique_ptr<Check> make_narrowed_world_matrix(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<NarrowedWorldMatrix>(rule, tables, out);
}

}  // namespace lwc::host
