// OpenGL 3.3 core declarations. The functions are resolved from libOSMesa at link time (it
// exports the whole GL API), so no loader is needed. Include this instead of <GL/gl.h>.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
