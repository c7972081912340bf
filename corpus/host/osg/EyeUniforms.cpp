// Uniforms set from double positions in an OpenSceneGraph-style globe renderer.
#include "osg_mini.h"

void UpdateEye(osg::Uniform* eyeUniform, osg::StateSet* stateSet, const osg::Vec3d& eye, const osg::Vec3d& center)
{
  eyeUniform->set(osg::Vec3f(eye));
  eyeUniform->set(eye);
  stateSet->addUniform(new osg::Uniform("oe_center", center));
  // Right: the difference of two positions, in double.
  eyeUniform->set(osg::Vec3f(eye - center));
}

// Right: a copy of the position made a direction in place before it is uploaded.
void UpdateSun(osg::Uniform* sunDirection, const osg::Vec3d& position)
{
  osg::Vec3d sun = position;
  sun.normalize();
  sunDirection->set(osg::Vec3f(sun));
}

// Right: a member named as a position, made a direction in place before it is uploaded.
struct LightingData {
  osg::Vec3d eyePos;
};

void UpdateEyeDirection(osg::Uniform* eyeDirection, LightingData& data, const osg::Vec3d& eye)
{
  data.eyePos = eye;
  data.eyePos.normalize();
  eyeDirection->set(osg::Vec3f(data.eyePos));
}
