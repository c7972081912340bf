// lwc-host-narrowed-world-upload: a double world position narrowed to float on its way to the GPU.
#include "host/check.h"
#include "host/checks/narrowing.h"

#include <clang/Lex/Lexer.h>

namespace lwc::host {

using namespace clang;

namespace {

class NarrowedWorldUpload : public UploadCheck {
 public:
  using UploadCheck::UploadCheck;

  void upload(const Upload& found, const ast_matchers::MatchFinder::MatchResult& match) override {
    if (found.value.kind != Kind::position || !found.gpu) return;
    const Upload* up = &found;
    const SourceManager& sm = *match.SourceManager;
    const LangOptions& lang = match.Context->getLangOpts();
    Vars vars;
    std::string preview;
    Finding* finding = report_upload(*up, match, rule_, out_, tables_, "translated-position", vars, preview);
    if (!finding || preview.empty()) return;
    // Translated world: the camera subtracted in double, before the rounding.
    const Expr* value = strip(up->value_expr);
    // One component (`Location.Z`) takes the same component of the offset.
    if (up->value_expr->getType()->isBuiltinType()) {
      auto* component = dyn_cast<MemberExpr>(value);
      if (!component) {
        finding->withheld.push_back("translated: a scalar that is not a named component of the position");
        return;
      }
      preview += "." + component->getMemberDecl()->getNameAsString();
      vars["preview"] = preview;
    }
    bool wrap = isa<ConditionalOperator>(value) || (isa<BinaryOperator>(value) && !cast<BinaryOperator>(value)->isAdditiveOp() &&
                                                    !cast<BinaryOperator>(value)->isMultiplicativeOp());
    CharSourceRange range = CharSourceRange::getTokenRange(up->value_expr->getSourceRange());
    SourceLocation end = Lexer::getLocForEndOfToken(sm.getExpansionLoc(range.getEnd()), 0, sm, lang);
    std::vector<Reporter::Change> changes;
    if (wrap) changes.push_back({CharSourceRange::getCharRange(sm.getExpansionLoc(range.getBegin()), sm.getExpansionLoc(range.getBegin())), "("});
    changes.push_back({CharSourceRange::getCharRange(end, end), (wrap ? ")" : "") + std::string(" + ") + preview});
    out_.fix(*finding, rule_, "translated", vars, changes, sm, lang);
  }
};

}  // namespace

std::unique_ptr<Check> make_narrowed_world_upload(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<NarrowedWorldUpload>(rule, tables, out);
}

}  // namespace lwc::host
