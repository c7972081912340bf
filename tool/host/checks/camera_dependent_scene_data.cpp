// lwc-host-camera-dependent-scene-data: a model-view (or model-view-projection) matrix composed on
// the host and uploaded: camera-relative, so precise, but it makes per-object data depend on the
// camera, which GPU-resident scene data cannot keep.
#include "host/check.h"
#include "host/checks/narrowing.h"

namespace lwc::host {

using namespace clang;

namespace {

class CameraDependentSceneData : public Check {
 public:
  using Check::Check;
  void register_matchers(ast_matchers::MatchFinder&) override {}
  bool reads_narrowings() const override { return true; }

  void run(const ast_matchers::MatchFinder::MatchResult& match) override {
    std::optional<Upload> up = find_upload(match, tables_, Kind::model_view);
    if (!up || !up->gpu) return;
    World world(tables_, *match.Context);
    out_.report(rule_, *match.SourceManager, match.Context->getLangOpts(), up->narrowing->getSourceRange(),
                {{"narrowing", world.text(up->narrowing->getSourceRange())}, {"value", up->value.source}, {"sink", up->sink}});
  }
};

}  // namespace

std::unique_ptr<Check> make_camera_dependent_scene_data(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<CameraDependentSceneData>(rule, tables, out);
}

}  // namespace lwc::host
