// lwc-host-float-world-storage: an absolute world position or transform kept in float in CPU-side
// scene data, rounded there before any upload can do better.
#include "host/check.h"
#include "host/checks/narrowing.h"
#include "host/member_values.h"

namespace lwc::host {

using namespace clang;

namespace {

class FloatWorldStorage : public UploadCheck {
 public:
  using UploadCheck::UploadCheck;

  void upload(const Upload& found, const ast_matchers::MatchFinder::MatchResult& match) override {
    if (found.gpu || (found.value.kind != Kind::position && found.value.kind != Kind::matrix)) return;
    World world(tables_, *match.Context);
    out_.report(rule_, *match.SourceManager, match.Context->getLangOpts(), found.narrowing->getSourceRange(),
                {{"narrowing", world.text(found.narrowing->getSourceRange())},
                 {"what", found.value.kind == Kind::position ? "world position" : "world matrix"},
                 {"value", world.text(found.value.expr->getSourceRange())},
                 {"sink", found.sink}},
                name_rested_on(found.value));
  }
};

}  // namespace

std::unique_ptr<Check> make_float_world_storage(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<FloatWorldStorage>(rule, tables, out);
}

}  // namespace lwc::host
