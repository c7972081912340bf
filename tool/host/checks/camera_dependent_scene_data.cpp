// lwc-host-camera-dependent-scene-data: a model-view (or model-view-projection) matrix composed on
// the host and uploaded: camera-relative, so precise, but it makes per-object data depend on the
// camera, which GPU-resident scene data cannot keep.
#include "host/check.h"
#include "host/checks/narrowing.h"
#include "host/member_values.h"

namespace lwc::host {

using namespace clang;

namespace {

class CameraDependentSceneData : public UploadCheck {
 public:
  using UploadCheck::UploadCheck;

  void upload(const Upload& found, const ast_matchers::MatchFinder::MatchResult& match) override {
    if (found.value.kind != Kind::model_view || !found.gpu) return;
    const Upload* up = &found;
    World world(tables_, *match.Context);
    out_.report(rule_, *match.SourceManager, match.Context->getLangOpts(), up->narrowing->getSourceRange(),
                {{"narrowing", world.text(up->narrowing->getSourceRange())}, {"value", world.text(up->value.expr->getSourceRange())}, {"sink", up->sink}},
                name_rested_on(up->value));
  }
};

}  // namespace

std::unique_ptr<Check> make_camera_dependent_scene_data(const RuleInfo& rule, const Tables& tables, Reporter& out) {
  return std::make_unique<CameraDependentSceneData>(rule, tables, out);
}

}  // namespace lwc::host
