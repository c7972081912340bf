// lwc-host-narrowed-world-upload: a double world position narrowed to float on its way to the GPU.
#include "host/check.h"
#include "host/checks/high_low.h"
#include "host/checks/narrowing.h"

#include <clang/Lex/Lexer.h>

namespace lwc::host {

using namespace clang;

namespace {

class NarrowedWorldUpload : public PortedUploadCheck {
 public:
  using PortedUploadCheck::PortedUploadCheck;

  bool reports(const Upload& up) const override { return up.value.kind == Kind::position && up.gpu; }
  const char* port() const override { return "translated-position"; }

  // The camera subtracted in double before the rounding; "" when offered, else why not.
  std::string translated(const Upload& up, const CameraInScope& camera, Finding& finding, Vars& vars,
                         const ast_matchers::MatchFinder::MatchResult& match) override {
    const SourceManager& sm = *match.SourceManager;
    const LangOptions& lang = match.Context->getLangOpts();
    const Expr* value = strip(up.value_expr);
    std::string code = camera.code;
    const Expr* position = value;
    // One component (`Location.Z`) takes the same component of the camera.
    if (up.value_expr->getType()->isBuiltinType()) {
      auto* component = dyn_cast<MemberExpr>(value);
      if (!component) return "a scalar that is not a named component of the position";
      code += "." + component->getMemberDecl()->getNameAsString();
      position = component->getBase()->IgnoreParenImpCasts();
      // glm's `x` is a member of an anonymous union inside the vector.
      for (auto* m = dyn_cast<MemberExpr>(position); m && !m->getMemberDecl()->getIdentifier(); m = dyn_cast<MemberExpr>(position))
        position = m->getBase()->IgnoreParenImpCasts();
    }
    if (camera.subtract && World(tables_, *match.Context).text(position->getSourceRange()) == camera.code)
      return "the camera's own position, which is zero in translated world";
    std::string term = (camera.subtract ? " - " : " + ") + code;
    vars["translated"] = vars["value"] + term;
    // `a - b` plus the camera needs no brackets (+ and - associate left), a comparison or a choice
    // does; and `(float)P.X` and `P.cast<float>()` bind tighter than the sum, which goes in brackets of its own.
    bool wrap_value = isa<ConditionalOperator>(value) ||
                      (isa<BinaryOperator>(value) && !cast<BinaryOperator>(value)->isAdditiveOp() && !cast<BinaryOperator>(value)->isMultiplicativeOp());
    bool wrap_sum = isa<CStyleCastExpr, CXXMemberCallExpr>(up.narrowing) && !isa<ParenExpr>(up.value_expr->IgnoreImpCasts());
    CharSourceRange range = CharSourceRange::getTokenRange(up.value_expr->getSourceRange());
    SourceLocation begin = sm.getExpansionLoc(range.getBegin());
    SourceLocation end = Lexer::getLocForEndOfToken(sm.getExpansionLoc(range.getEnd()), 0, sm, lang);
    std::string open = std::string(wrap_sum ? "(" : "") + (wrap_value ? "(" : "");
    std::vector<Reporter::Change> changes;
    if (!open.empty()) changes.push_back({CharSourceRange::getCharRange(begin, begin), open});
    changes.push_back({CharSourceRange::getCharRange(end, end), (wrap_value ? ")" : "") + term + (wrap_sum ? ")" : "")});
    out_.fix(finding, rule_, "translated", vars, changes, sm, lang);
    return "";
  }
};

}  // namespace

std::unique_ptr<Check> make_narrowed_world_upload(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<NarrowedWorldUpload>(rule, tables, out);
}

}  // namespace lwc::host
