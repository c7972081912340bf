// A scene node kept in float, next to a pointer dragged over a canvas in an OpenSceneGraph-style
// application: only the first is a world position.
#include "osg_mini.h"

struct PlacedNode {
  osg::Vec3f position;
};

void Place(PlacedNode& node, const osg::Vec3d& position)
{
  node.position = position;
}

// Right: two numbers named as a position are the pointer's place in canvas pixels.
struct DragTracker {
  osg::Vec2f lastPos;
  osg::Vec2f lastDelta;
};

void OnDrag(DragTracker& drag, double u, double v, double width, double height)
{
  osg::Vec2d pos(u * width, (1 - v) * height);
  drag.lastDelta = pos - drag.lastPos;
  drag.lastPos = pos;
}
