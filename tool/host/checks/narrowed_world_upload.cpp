// lwc-host-narrowed-world-upload: a double world position narrowed to float on its way to the GPU.
#include "host/check.h"
#include "host/checks/narrowing.h"

#include <clang/Lex/Lexer.h>

namespace lwc::host {

using namespace clang;

namespace {

class NarrowedWorldUpload : public Check {
 public:
  using Check::Check;
  void register_matchers(ast_matchers::MatchFinder&) override {}
  bool reads_narrowings() const override { return true; }

  void run(const ast_matchers::MatchFinder::MatchResult& match) override {
    std::optional<Upload> up = find_upload(match, tables_, Kind::position);
    if (!up || !up->gpu) return;
    const SourceManager& sm = *match.SourceManager;
    const LangOptions& lang = match.Context->getLangOpts();
    World world(tables_, *match.Context);
    Vars vars{{"narrowing", world.text(up->narrowing->getSourceRange())}, {"type", up->narrowing_type},
              {"value", up->value.source}, {"sink", up->sink}, {"field", up->field.empty() ? "the uploaded value" : "`" + up->field + "`"}};
    Finding* finding = out_.report(rule_, sm, lang, up->narrowing->getSourceRange(), vars);
    if (!finding) return;
    if (!up->field.empty()) finding->facts = {{"shader-parameter", up->field}, {"port", "translated-position"}};
    // Translated world: the camera subtracted in double, before the rounding.
    std::string preview = preview_translation(up->narrowing, *match.Context, tables_);
    if (preview.empty()) {
      finding->withheld.push_back("translated: no view in scope (a parameter or local of a view type, rules/host-world.json \"views\")");
      return;
    }
    const Expr* value = strip(up->value_expr);
    // One component (`Location.Z`) takes the same component of the offset.
    if (up->value_expr->getType()->isBuiltinType()) {
      auto* component = dyn_cast<MemberExpr>(value);
      if (!component) {
        finding->withheld.push_back("translated: a scalar that is not a named component of the position");
        return;
      }
      preview += "." + component->getMemberDecl()->getNameAsString();
    }
    bool wrap = isa<ConditionalOperator>(value) || (isa<BinaryOperator>(value) && !cast<BinaryOperator>(value)->isAdditiveOp() &&
                                                    !cast<BinaryOperator>(value)->isMultiplicativeOp());
    CharSourceRange range = CharSourceRange::getTokenRange(up->value_expr->getSourceRange());
    SourceLocation end = Lexer::getLocForEndOfToken(sm.getExpansionLoc(range.getEnd()), 0, sm, lang);
    std::vector<Reporter::Change> changes;
    if (wrap) changes.push_back({CharSourceRange::getCharRange(sm.getExpansionLoc(range.getBegin()), sm.getExpansionLoc(range.getBegin())), "("});
    changes.push_back({CharSourceRange::getCharRange(end, end), (wrap ? ")" : "") + std::string(" + ") + preview});
    vars["preview"] = preview;
    out_.fix(*finding, rule_, "translated", vars, changes, sm, lang);
  }
};

}  // namespace

std::unique_ptr<Check> make_narrowed_world_upload(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<NarrowedWorldUpload>(rule, tables, out);
}

}  // namespace lwc::host
