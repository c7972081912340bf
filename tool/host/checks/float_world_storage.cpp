// lwc-host-float-world-storage: an absolute world position or transform kept in float in CPU-side
// scene data, rounded there before any upload can do better.
#include "host/check.h"
#include "host/checks/narrowing.h"

namespace lwc::host {

using namespace clang;

namespace {

class FloatWorldStorage : public Check {
 public:
  using Check::Check;
  void register_matchers(ast_matchers::MatchFinder&) override {}
  bool reads_narrowings() const override { return true; }

  void run(const ast_matchers::MatchFinder::MatchResult& match) override {
    for (Kind kind : {Kind::position, Kind::matrix}) {
      std::optional<Upload> up = find_upload(match, tables_, kind);
      if (!up || up->gpu) continue;
      World world(tables_, *match.Context);
      out_.report(rule_, *match.SourceManager, match.Context->getLangOpts(), up->narrowing->getSourceRange(),
                  {{"narrowing", world.text(up->narrowing->getSourceRange())},
                   {"what", kind == Kind::position ? "world position" : "world matrix"},
                   {"value", up->value.source},
                   {"sink", up->sink}});
    }
  }
};

}  // namespace

std::unique_ptr<Check> make_float_world_storage(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<FloatWorldStorage>(rule, tables, out);
}

}  // namespace lwc::host
