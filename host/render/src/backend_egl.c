/* The EGL surfaceless backend: a GPU's (or llvmpipe's) context with no
 * display and no surface. Measured on Mesa 22.3.6:
 * eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, ...),
 * EGL_NO_CONFIG_KHR, no surface and eglBindAPI(EGL_OPENGL_API) give a 4.5
 * core context; drawing into a framebuffer object and glReadPixels work.
 * Mesa dropped OSMesa in 25.1, so newer systems have only this one. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "render_internal.h"

typedef struct egl_state {
  EGLDisplay dpy;
  EGLContext ctx;
} egl_state;

/* The surfaceless display is one per process, shared by every renderer,
 * and is never terminated: eglTerminate lets Mesa unload its driver, which
 * leaves behind allocations no one can free or even name (the code that
 * made them is gone), at every create-destroy cycle; kept loaded, the
 * driver is loaded once. */

static mr_gl_proc egl_get(const char *name) {
  __eglMustCastToProperFunctionPointerType p = eglGetProcAddress(name);
  mr_gl_proc out;
  memcpy(&out, &p, sizeof out);
  return out;
}

static int egl_make_current(mr_render *r) {
  egl_state *s = r->bk;
  return eglMakeCurrent(s->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, s->ctx) ? 0 : -1;
}

static void egl_stop(mr_render *r) {
  egl_state *s = r->bk;
  if (!s) return;
  if (s->ctx != EGL_NO_CONTEXT) {
    eglMakeCurrent(s->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(s->dpy, s->ctx);
  }
  free(s);
  r->bk = NULL;
}

static EGLDisplay egl_display(char *msg, size_t msg_size) {
  const char *ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!ext || !strstr(ext, "EGL_MESA_platform_surfaceless")) {
    snprintf(msg, msg_size, "EGL: no surfaceless platform (EGL_MESA_platform_surfaceless)");
    return EGL_NO_DISPLAY;
  }
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_display = NULL;
  __eglMustCastToProperFunctionPointerType p = eglGetProcAddress("eglGetPlatformDisplayEXT");
  memcpy(&get_display, &p, sizeof get_display);
  if (!get_display) {
    snprintf(msg, msg_size, "EGL: no eglGetPlatformDisplayEXT");
    return EGL_NO_DISPLAY;
  }
  EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
  if (dpy == EGL_NO_DISPLAY) snprintf(msg, msg_size, "EGL: no surfaceless display");
  return dpy;
}

static int egl_fail(mr_render *r, char *msg, size_t msg_size, const char *what) {
  snprintf(msg, msg_size, "EGL: %s (error 0x%x)", what, (unsigned)eglGetError());
  egl_stop(r);
  return -1;
}

static int egl_start(mr_render *r, const mr_render_def *def, char *msg, size_t msg_size) {
  (void)def;
  egl_state *s = calloc(1, sizeof *s);
  if (!s) {
    snprintf(msg, msg_size, "out of memory");
    return -1;
  }
  s->dpy = EGL_NO_DISPLAY;
  s->ctx = EGL_NO_CONTEXT;
  r->bk = s;
  EGLDisplay dpy = egl_display(msg, msg_size);
  if (dpy == EGL_NO_DISPLAY) {
    egl_stop(r);
    return -1;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor))
    return egl_fail(r, msg, msg_size, "eglInitialize failed");
  s->dpy = dpy;
  if (!eglBindAPI(EGL_OPENGL_API)) return egl_fail(r, msg, msg_size, "no desktop OpenGL");
  const EGLint attribs[] = { EGL_CONTEXT_MAJOR_VERSION,
                             3,
                             EGL_CONTEXT_MINOR_VERSION,
                             3,
                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                             EGL_NONE };
  s->ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (s->ctx == EGL_NO_CONTEXT)
    return egl_fail(r, msg, msg_size, "no OpenGL 3.3 core context without a config");
  if (egl_make_current(r) != 0)
    return egl_fail(r, msg, msg_size, "cannot make the context current without a surface");
  if (mr_gl_load(&r->gl, egl_get, msg, msg_size) != 0) {
    egl_stop(r);
    return -1;
  }
  return 0;
}

const mr_backend_ops mr_backend_egl_ops = { MR_RENDER_EGL, egl_start, egl_make_current, egl_stop };
