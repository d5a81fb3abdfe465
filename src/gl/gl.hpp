// The one header through which clothlab's GL code reaches OpenGL.
// The GL code is compiled up to four times from the same sources:
//  - the window build (CLOTHLAB_GL_WINDOW) loads the functions with GLEW in a GLFW context (and
//    so does the off-screen build of a system with neither OSMesa nor EGL: a hidden window);
//  - the off-screen build (CLOTHLAB_GL_OSMESA) calls libOSMesa's exported entry points
//    directly (GLEW cannot load functions in an OSMesa context);
//  - the EGL build (CLOTHLAB_GL_EGL) calls glvnd's libOpenGL, which dispatches to the vendor
//    of the current EGL context (a GPU's driver, or Mesa);
//  - the web build (CLOTHLAB_GL_WEB, WebAssembly) calls OpenGL ES 3.0, which emscripten maps
//    onto the browser's WebGL2: no compute shaders, no polygon mode, and a query's result only
//    in a later frame. The few places where the GL code differs there are marked with
//    #if defined(CLOTHLAB_GL_WEB).
#pragma once

#if defined(CLOTHLAB_GL_WINDOW)
#include <GL/glew.h>
#elif defined(CLOTHLAB_GL_OSMESA) || defined(CLOTHLAB_GL_EGL)
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
#elif defined(CLOTHLAB_GL_WEB)
#include <GLES3/gl3.h>
#else
// (src/gl/CMakeLists.txt defines the first three, the web build's CMake the last)
#error "define CLOTHLAB_GL_WINDOW, CLOTHLAB_GL_OSMESA, CLOTHLAB_GL_EGL or CLOTHLAB_GL_WEB"
#endif
