// Model matrices built with glm's translate, rotate and scale. A move by a world position places a
// body in the world; a move by the negated eye takes the world into the camera's frame.
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

struct ShaderProgram {
  void setMat4(const char* name, const glm::mat4& value) const;
};

struct Body {
  glm::dvec3 position;  // metres from the system's barycentre
  glm::dquat orientation;
  double radius;
};

// Positives: the matrices hold the body's world position, rounded to float at the upload.
void draw_body(const ShaderProgram& program, const Body& body)
{
  glm::dmat4 placement = glm::scale(glm::translate(glm::dmat4(1.0), body.position), glm::dvec3(body.radius));
  program.setMat4("model", glm::mat4(placement));
}

void draw_ring(const ShaderProgram& program, const Body& body, double tilt)
{
  glm::dmat4 ring = glm::rotate(glm::translate(glm::dmat4(), body.position), tilt, glm::dvec3(1.0, 0.0, 0.0));
  program.setMat4("ringModel", glm::mat4(ring * glm::mat4_cast(body.orientation)));
}

// Negatives: each is moved by the body's position relative to the eye, taken in double.
void draw_body_from(const ShaderProgram& program, const Body& body, const glm::dvec3& eye)
{
  glm::dmat4 placement = glm::translate(glm::dmat4(1.0), body.position - eye);
  program.setMat4("model", glm::mat4(glm::scale(placement, glm::dvec3(body.radius))));
  // The same difference written as the eye's negation plus the position.
  glm::dmat4 moved = glm::translate(glm::dmat4(1.0), -eye + body.position);
  program.setMat4("model", glm::mat4(moved));
}

// The move into the camera's frame, then the body's placement: the translations cancel in double.
void draw_body_in_camera_frame(const ShaderProgram& program, const Body& body, const glm::dvec3& eye)
{
  glm::dmat4 toCamera = glm::translate(glm::dmat4(1.0), -eye);
  glm::dmat4 placement = glm::translate(glm::dmat4(1.0), body.position);
  program.setMat4("modelView", glm::mat4(toCamera * placement));
}

// A local offset moved by a matrix the unit does not know: nothing is said of it.
void draw_part(const ShaderProgram& program, const glm::dmat4& parent, const glm::dvec3& attachment)
{
  program.setMat4("model", glm::mat4(glm::translate(parent, attachment)));
}
