/* The window and the renderer wired together, as a program does it: the
 * renderer draws into the GL context the window made, loading its entry
 * points through the window and asking it to show each frame. Neither
 * library knows the other; this is the one place that knows both. */
#ifndef MR_GLUE_H
#define MR_GLUE_H

#include "mr_render.h"
#include "mr_window.h"

/* w's context as the renderer takes it (mr_render_def.context); w must
 * outlive the renderer. */
mr_render_context mr_glue_context(mr_window *w);

/* The renderer's choice of OpenGL as the window's. */
mr_window_gl mr_glue_gl(mr_render_gl gl);

#endif
