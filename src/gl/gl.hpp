// The one header through which clothlab's GL code reaches OpenGL.
// The GL code is compiled three times from the same sources:
//  - the window build (CLOTHLAB_GL_WINDOW) loads the functions with GLEW in a GLFW context;
//  - the off-screen build (CLOTHLAB_GL_OSMESA) calls libOSMesa's exported entry points
//    directly (GLEW cannot load functions in an OSMesa context);
//  - the EGL build (CLOTHLAB_GL_EGL) calls glvnd's libOpenGL, which dispatches to the vendor
//    of the current EGL context (a GPU's driver, or Mesa).
#pragma once

#if defined(CLOTHLAB_GL_WINDOW)
#include <GL/glew.h>
#elif defined(CLOTHLAB_GL_OSMESA) || defined(CLOTHLAB_GL_EGL)
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
#else
#error "define CLOTHLAB_GL_WINDOW, CLOTHLAB_GL_OSMESA or CLOTHLAB_GL_EGL (src/gl/CMakeLists.txt)"
#endif
