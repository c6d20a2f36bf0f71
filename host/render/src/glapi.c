/* Which OpenGL: the names the options use, and what the context turned
 * out to be (its strings for logs, a short version for summary lines). */
#include <stdio.h>
#include <string.h>

#include "render_internal.h"

static const char *const gl_names[] = { "auto", "core", "es3" };

const char *mr_render_gl_name(mr_render_gl g) {
  if ((int)g < 0 || (size_t)g >= sizeof gl_names / sizeof gl_names[0]) return "?";
  return gl_names[g];
}

int mr_render_gl_parse(const char *name, mr_render_gl *out) {
  if (!name || !out) return -1;
  for (size_t i = 0; i < sizeof gl_names / sizeof gl_names[0]; i++) {
    if (strcmp(name, gl_names[i]) == 0) {
      *out = (mr_render_gl)i;
      return 0;
    }
  }
  return -1;
}

/* GL_VERSION reads "4.5 (Core Profile) Mesa ..." on the desktop but
 * "OpenGL ES 3.2 Mesa ..." in ES: the description says "OpenGL" once. */
void mr_gl_describe(mr_render *r) {
  const char *renderer = (const char *)r->gl.GetString(GL_RENDERER);
  const char *version = (const char *)r->gl.GetString(GL_VERSION);
  if (!version) version = "?";
  const char *api = strncmp(version, "OpenGL", 6) == 0 ? "" : "OpenGL ";
  snprintf(r->description, sizeof r->description, "%s, %s%s", renderer ? renderer : "?", api,
           version);
  GLint major = 0, minor = 0;
  r->gl.GetIntegerv(GL_MAJOR_VERSION, &major);
  r->gl.GetIntegerv(GL_MINOR_VERSION, &minor);
  snprintf(r->gl_version, sizeof r->gl_version, r->gles ? "OpenGL ES %d.%d" : "OpenGL %d.%d core",
           (int)major, (int)minor);
  r->software = renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe") ||
                             strstr(renderer, "swrast"));
}

mr_render_gl mr_render_gl_of(const mr_render *r) {
  if (!r) return MR_RENDER_GL_AUTO;
  return r->gles ? MR_RENDER_GL_ES3 : MR_RENDER_GL_CORE;
}

const char *mr_render_gl_version(const mr_render *r) {
  return r ? r->gl_version : "";
}
