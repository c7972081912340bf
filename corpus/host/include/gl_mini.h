// The few OpenGL entry points the host corpus calls, declared for lwcport's corpus (no GL headers needed).
#pragma once
typedef int GLint;
typedef int GLsizei;
typedef float GLfloat;
typedef unsigned char GLboolean;
#define GL_FALSE 0
#define GL_ARRAY_BUFFER 0x8892
#define GL_STATIC_DRAW 0x88E4
#define GL_UNIFORM_BUFFER 0x8A11
extern "C" {
void glUniform1f(GLint location, GLfloat v0);
void glUniform3f(GLint location, GLfloat v0, GLfloat v1, GLfloat v2);
void glUniform2fv(GLint location, GLsizei count, const GLfloat* value);
void glUniform3fv(GLint location, GLsizei count, const GLfloat* value);
void glUniformMatrix4fv(GLint location, GLsizei count, GLboolean transpose, const GLfloat* value);
GLint glGetUniformLocation(unsigned program, const char* name);
void glBufferData(unsigned target, long size, const void* data, unsigned usage);
void glBufferSubData(unsigned target, long offset, long size, const void* data);
void glNamedBufferData(unsigned buffer, long size, const void* data, unsigned usage);
void glVertexArrayVertexBuffer(unsigned vaobj, unsigned bindingindex, unsigned buffer, long offset, GLsizei stride);
}
