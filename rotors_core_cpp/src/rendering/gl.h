// OpenGL 3.3 core with its function prototypes (Mesa's libGL exports them): one place that
// includes the header the same way for every renderer file.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#endif
#include <GL/glcorearb.h>
