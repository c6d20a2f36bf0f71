/* Loading the GL table (see gl.h for why the renderer never calls gl*). */
#include "gl.h"

#include <stdio.h>
#include <string.h>

int mr_gl_load(mr_gl *gl, mr_gl_get_proc get, char *msg, size_t msg_size) {
  memset(gl, 0, sizeof *gl);
  /* Each entry: look it up as "gl" NAME; a missing one stops the load. A
   * function pointer is copied through memcpy, which C allows between
   * pointer-to-function types of equal size. */
#define MR_GL_LOAD(type, name)                                              \
  {                                                                         \
    mr_gl_proc p = get("gl" #name);                                         \
    if (!p) {                                                               \
      snprintf(msg, msg_size, "the GL entry point gl%s is missing", #name); \
      return -1;                                                            \
    }                                                                       \
    type f;                                                                 \
    memcpy(&f, &p, sizeof f);                                               \
    gl->name = f;                                                           \
  }
  MR_GL_FUNCTIONS(MR_GL_LOAD)
#undef MR_GL_LOAD
  return 0;
}
