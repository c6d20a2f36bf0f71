/* One frame, in the order it is drawn: the sun's shadow map (when it has
 * moved), the sky (the clear colour), the lit scenery and models, the
 * stars, the rigging; then the frame is resolved (or its edges smoothed)
 * and the on-screen display drawn over it. */
#include <math.h>

#include "render_internal.h"

/* The camera, in cglm's float matrices (mr_render_view is double). */
static void frame_camera(const mr_render *r, const mr_render_view *v, mr_frame *f) {
  vec3 eye, target, up;
  for (int k = 0; k < 3; k++) {
    eye[k] = (float)v->eye[k];
    target[k] = (float)v->target[k];
    up[k] = (float)v->up[k];
  }
  if (glm_vec3_norm(up) < 1e-6f) glm_vec3_copy((vec3){ 0, 1, 0 }, up);
  double fov = v->fov_deg > 1 && v->fov_deg < 179 ? v->fov_deg : 45;
  glm_lookat(eye, target, up, f->view);
  glm_perspective((float)(fov * GLM_PI / 180.0), (float)r->width / (float)r->height, 0.05f, 100.0f,
                  f->proj);
  glm_mat4_mul(f->proj, f->view, f->view_proj);
  glm_vec3_copy(eye, f->eye);
}

static int view_is_finite(const mr_render_view *v) {
  for (int k = 0; k < 3; k++)
    if (!isfinite(v->eye[k]) || !isfinite(v->target[k]) || !isfinite(v->up[k])) return 0;
  return isfinite(v->fov_deg) && isfinite(v->time_of_day);
}

/* lookAt needs a direction (eye != target) and an up vector not along it:
 * otherwise its basis is zero or NaN and the frame is only sky, drawn
 * without complaint. The bound is relative, so a view looking nearly
 * straight down (elevation 89 degrees) still passes. */
static int view_has_basis(const mr_render_view *v) {
  double d[3], c[3];
  for (int k = 0; k < 3; k++) d[k] = v->target[k] - v->eye[k];
  c[0] = d[1] * v->up[2] - d[2] * v->up[1];
  c[1] = d[2] * v->up[0] - d[0] * v->up[2];
  c[2] = d[0] * v->up[1] - d[1] * v->up[0];
  double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double uu = v->up[0] * v->up[0] + v->up[1] * v->up[1] + v->up[2] * v->up[2];
  double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
  return dd > 0 && uu > 0 && cc > 1e-12 * dd * uu;
}

mr_render_status mr_render_draw(mr_render *r, const mr_draw_list *list,
                                const mr_render_view *view) {
  if (!r || !view || !view_is_finite(view) || !view_has_basis(view)) return MR_RENDER_ERR_ARG;
  if (r->ops->make_current(r) != 0) return MR_RENDER_ERR_GL;
  const mr_gl *gl = &r->gl;
  mr_frame f;
  frame_camera(r, view, &f);
  mr_sky_light(&r->stage, view->time_of_day, &f);
  mr_follow_spot_frame(r, list, &f);
  mr_shadow_draw(r, list, &f);

  mr_still_rects still;
  bool kept = mr_still_draw(r, list, &f, &still);
  if (!kept) {
    mr_fbo_bind_draw(r);
    gl->ClearColor(mr_srgb(f.sky[0]), mr_srgb(f.sky[1]), mr_srgb(f.sky[2]), 1);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  }
  gl->Enable(GL_DEPTH_TEST);
  gl->DepthFunc(GL_LEQUAL);
  /* Model files do not agree on winding, and the floor and backdrop are
   * seen from both sides: nothing is culled. */
  gl->Disable(GL_CULL_FACE);
  mr_scene_draw_lit(r, list, &f, kept ? &still : NULL);
  mr_sky_draw_stars(r, &f);
  if (view->show_rigging && list) mr_lines_draw(r, list->lines, list->n_lines, &f);
  gl->Disable(GL_DEPTH_TEST);
  /* The text goes on after the resolve (or the smoothing), sharp. */
  mr_fbo_resolve(r, list, &f);
  mr_text_draw(r, view->osd, view->n_osd);
  gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
  r->drawn = true;
  return gl->GetError() == GL_NO_ERROR ? MR_RENDER_OK : MR_RENDER_ERR_GL;
}
