/* The EGL surfaceless backend: a GPU's (or llvmpipe's) context with no
 * display and no surface. Measured on Mesa 22.3.6:
 * eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, ...),
 * EGL_NO_CONFIG_KHR, no surface and eglBindAPI(EGL_OPENGL_API) give a 4.5
 * core context; eglBindAPI(EGL_OPENGL_ES_API) and a 3.0 context give
 * OpenGL ES 3.2. Drawing into a framebuffer object and glReadPixels work
 * in both. Mesa dropped OSMesa in 25.1, so newer systems have only this
 * one. def.gl AUTO asks for desktop OpenGL 3.3 core first and OpenGL ES
 * 3.0 when the display has no desktop OpenGL (a Raspberry Pi's V3D gives
 * desktop 3.1 only, and ES 3.1). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "render_internal.h"

typedef struct egl_state {
  EGLDisplay dpy;
  EGLContext ctx;
  EGLenum api; /* EGL_OPENGL_API or EGL_OPENGL_ES_API: the context's */
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

/* A thread has one current context per client API, and EGL_NO_CONTEXT
 * releases the bound API's: the context's own API is bound first. */
static int egl_make_current(mr_render *r) {
  egl_state *s = r->bk;
  if (!eglBindAPI(s->api)) return -1;
  return eglMakeCurrent(s->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, s->ctx) ? 0 : -1;
}

static void egl_stop(mr_render *r) {
  egl_state *s = r->bk;
  if (!s) return;
  if (s->ctx != EGL_NO_CONTEXT) {
    eglBindAPI(s->api);
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

/* A desktop OpenGL 3.3 core context, or EGL_NO_CONTEXT and why. */
static EGLContext core_context(EGLDisplay dpy, char *why, size_t why_size) {
  if (!eglBindAPI(EGL_OPENGL_API)) {
    snprintf(why, why_size, "the display offers no desktop OpenGL");
    return EGL_NO_CONTEXT;
  }
  const EGLint attribs[] = { EGL_CONTEXT_MAJOR_VERSION,
                             3,
                             EGL_CONTEXT_MINOR_VERSION,
                             3,
                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                             EGL_NONE };
  EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (ctx == EGL_NO_CONTEXT)
    snprintf(why, why_size, "no OpenGL 3.3 core context without a config (error 0x%x)",
             (unsigned)eglGetError());
  return ctx;
}

/* An OpenGL ES 3.0 (or later) context, or EGL_NO_CONTEXT and why. */
static EGLContext es_context(EGLDisplay dpy, char *why, size_t why_size) {
  /* Any surface type: a config asks for a window by default, and the
   * surfaceless display's are pbuffers only. */
  const EGLint want[] = { EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, EGL_DONT_CARE,
                          EGL_NONE };
  EGLConfig config;
  EGLint n = 0;
  if (!eglChooseConfig(dpy, want, &config, 1, &n) || n < 1) {
    snprintf(why, why_size, "the display offers no OpenGL ES 3 (EGL_OPENGL_ES3_BIT)");
    return EGL_NO_CONTEXT;
  }
  if (!eglBindAPI(EGL_OPENGL_ES_API)) {
    snprintf(why, why_size, "the display offers no OpenGL ES");
    return EGL_NO_CONTEXT;
  }
  const EGLint attribs[] = { EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE };
  EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (ctx == EGL_NO_CONTEXT)
    snprintf(why, why_size, "no OpenGL ES 3.0 context without a config (error 0x%x)",
             (unsigned)eglGetError());
  return ctx;
}

/* The context def.gl asks for: core, ES 3.0, or (AUTO) core else ES. */
static int egl_context(mr_render *r, mr_render_gl want, char *msg, size_t msg_size) {
  egl_state *s = r->bk;
  char why_core[160] = "", why_es[160] = "";
  if (want != MR_RENDER_GL_ES3) {
    s->api = EGL_OPENGL_API;
    s->ctx = core_context(s->dpy, why_core, sizeof why_core);
  }
  if (s->ctx == EGL_NO_CONTEXT && want != MR_RENDER_GL_CORE) {
    s->api = EGL_OPENGL_ES_API;
    s->ctx = es_context(s->dpy, why_es, sizeof why_es);
    r->gles = s->ctx != EGL_NO_CONTEXT;
  }
  if (s->ctx != EGL_NO_CONTEXT) return 0;
  if (want == MR_RENDER_GL_AUTO)
    snprintf(msg, msg_size, "EGL: %s, and %s", why_core, why_es);
  else
    snprintf(msg, msg_size, "EGL: %s", want == MR_RENDER_GL_CORE ? why_core : why_es);
  egl_stop(r);
  return -1;
}

static int egl_start(mr_render *r, const mr_render_def *def, char *msg, size_t msg_size) {
  egl_state *s = calloc(1, sizeof *s);
  if (!s) {
    snprintf(msg, msg_size, "out of memory");
    return -1;
  }
  s->dpy = EGL_NO_DISPLAY;
  s->ctx = EGL_NO_CONTEXT;
  s->api = EGL_OPENGL_API;
  r->bk = s;
  r->gles = false;
  EGLDisplay dpy = egl_display(msg, msg_size);
  if (dpy == EGL_NO_DISPLAY) {
    egl_stop(r);
    return -1;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor))
    return egl_fail(r, msg, msg_size, "eglInitialize failed");
  s->dpy = dpy;
  if (egl_context(r, def->gl, msg, msg_size) != 0) return -1;
  if (egl_make_current(r) != 0)
    return egl_fail(r, msg, msg_size, "cannot make the context current without a surface");
  if (mr_gl_load(&r->gl, egl_get, msg, msg_size) != 0) {
    egl_stop(r);
    return -1;
  }
  return 0;
}

const mr_backend_ops mr_backend_egl_ops = { MR_RENDER_EGL, egl_start, egl_make_current, egl_stop };
