// The one header through which clothlab's GL code reaches OpenGL.
// The GL code is compiled twice from the same sources (shared/notes/opengl-stack.md):
//  - the window build (CLOTHLAB_GL_WINDOW) loads the functions with GLEW in a GLFW context;
//  - the off-screen build (CLOTHLAB_GL_OSMESA) calls libOSMesa's exported entry points
//    directly (GLEW cannot load functions in an OSMesa context).
#pragma once

#if defined(CLOTHLAB_GL_WINDOW)
#include <GL/glew.h>
#elif defined(CLOTHLAB_GL_OSMESA)
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
#else
#error "define CLOTHLAB_GL_WINDOW or CLOTHLAB_GL_OSMESA (done by src/gl/CMakeLists.txt)"
#endif
