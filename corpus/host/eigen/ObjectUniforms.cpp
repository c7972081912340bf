// A renderer on Eigen with world positions and transforms in double: Eigen converts only through
// `cast<float>()`, which is where the rounding happens.
#include <Eigen/Dense>
#include <Eigen/Geometry>

struct Observer {
  Eigen::Vector3d position;
};

struct ObjectUniforms {
  Eigen::Vector3f objectPosition;
  float radius;
  Eigen::Matrix4f model;
};

void FillObject(ObjectUniforms& uniforms, const Eigen::Vector3d& worldPosition, const Eigen::Affine3d& worldTransform, const Observer& observer)
{
  uniforms.objectPosition = worldPosition.cast<float>();
  uniforms.model = worldTransform.matrix().cast<float>();
  // Right: relative to the observer, in double.
  uniforms.objectPosition = (worldPosition - observer.position).cast<float>();
  // A direction is not a position.
  const Eigen::Vector3d sunDirection = worldPosition.normalized();
  Eigen::Vector3f direction = sunDirection.cast<float>();
  (void)direction;
}

void FillWithoutObserver(ObjectUniforms& uniforms, const Eigen::Vector3d& worldPosition)
{
  uniforms.objectPosition = worldPosition.cast<float>();
}

// A model-view product in double (the translations cancel), behind a factor no table knows, then
// inverted: camera-relative, not a world matrix, however deep the product is.
Eigen::Matrix4d DepthCorrection();

struct ViewState {
  Eigen::Matrix4f modelViewInverse;
};

void KeepView(ViewState& state, const Eigen::Matrix4d& view, const Eigen::Matrix4d& model)
{
  Eigen::Matrix4d mv = DepthCorrection() * view * model;
  Eigen::Matrix4d mvInv = mv.inverse();
  state.modelViewInverse = mvInv.cast<float>();
}

// The view reached through more steps than the world model follows (each copy is two): that factor
// is cut off, and a product with a factor cut off is not known; it is not `model`'s world matrix.
void KeepViewBeyondTheLimit(ViewState& state, const Eigen::Matrix4d& view, const Eigen::Matrix4d& model)
{
  Eigen::Matrix4d v1 = view, v2 = v1, v3 = v2, v4 = v3, v5 = v4, v6 = v5, v7 = v6;
  Eigen::Matrix4d mv = DepthCorrection() * v7 * model;
  Eigen::Matrix4d mvInv = mv.inverse();
  state.modelViewInverse = mvInv.cast<float>();
}
