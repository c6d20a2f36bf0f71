/* The sun's shadow: a depth map seen from the sun through an orthographic
 * box around the stage, drawn before each frame from the models that
 * cast; the lit pass compares against it with 3 x 3 percentage-closer
 * filtering (shader_src.c). */
#include <math.h>
#include <stdio.h>

#include "render_internal.h"

int mr_shadow_create(mr_render *r, char *msg, size_t msg_size) {
  const mr_gl *gl = &r->gl;
  GLint max_side = 0;
  gl->GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  /* Without shadows the map is one texel, so the shader's sampler always
   * has a depth texture behind it. */
  int side = r->stage.lights.shadows ? r->stage.lights.shadow_size : 1;
  if (side < 1) side = 2048;
  if (side > max_side) side = max_side;
  r->shadow_size = side;
  gl->GenTextures(1, &r->shadow_tex);
  gl->BindTexture(GL_TEXTURE_2D, r->shadow_tex);
  gl->TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, side, side, 0, GL_DEPTH_COMPONENT,
                 GL_UNSIGNED_INT, NULL);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  gl->GenFramebuffers(1, &r->shadow_fbo);
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->shadow_fbo);
  gl->FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, r->shadow_tex, 0);
  const GLenum none = GL_NONE; /* glDrawBuffers: glDrawBuffer is desktop only */
  gl->DrawBuffers(1, &none);
  gl->ReadBuffer(GL_NONE);
  GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (st != GL_FRAMEBUFFER_COMPLETE) {
    snprintf(msg, msg_size, "the shadow map's framebuffer is incomplete (0x%x)", (unsigned)st);
    return -1;
  }
  return 0;
}

void mr_shadow_destroy(mr_render *r) {
  if (r->shadow_fbo) r->gl.DeleteFramebuffers(1, &r->shadow_fbo);
  if (r->shadow_tex) r->gl.DeleteTextures(1, &r->shadow_tex);
  r->shadow_fbo = r->shadow_tex = 0;
}

/* The sun's view: a box of half-side R about the stage's middle, R the
 * floor's half diagonal (and at least reaching the backdrop). */
static void light_matrix(const mr_render *r, const mr_frame *f, mat4 out) {
  const mr_stage_def *s = &r->stage;
  float R = (float)(s->floor_size * 0.5 * 1.4143);
  if (s->backdrop && R < (float)s->backdrop_distance + 0.5f) R = (float)s->backdrop_distance + 0.5f;
  if (R < 2) R = 2;
  vec3 centre = { 0, (float)s->floor_height, 0 }, eye, up = { 0, 0, 1 };
  glm_vec3_scale((float *)f->sun_dir, 2 * R, eye);
  glm_vec3_add(eye, centre, eye);
  /* Up must not be along the sun: z is never, while the sun stays in
   * the x-y plane tilted towards +z (sky.c). */
  if (fabsf(f->sun_dir[2]) > 0.99f) {
    up[1] = 1;
    up[2] = 0;
  }
  mat4 view, proj;
  glm_lookat(eye, centre, up, view);
  glm_ortho(-R, R, -R, R, 0.01f, 4 * R, proj);
  glm_mat4_mul(proj, view, out);
}

void mr_shadow_draw(mr_render *r, const mr_draw_list *list, mr_frame *f) {
  const mr_gl *gl = &r->gl;
  light_matrix(r, f, f->light_vp);
  if (!f->shadows || !list) return;
  gl->ActiveTexture(GL_TEXTURE1);
  gl->BindTexture(GL_TEXTURE_2D, 0);
  gl->BindFramebuffer(GL_FRAMEBUFFER, r->shadow_fbo);
  gl->Viewport(0, 0, r->shadow_size, r->shadow_size);
  gl->Clear(GL_DEPTH_BUFFER_BIT);
  gl->Enable(GL_DEPTH_TEST);
  gl->Enable(GL_POLYGON_OFFSET_FILL);
  gl->PolygonOffset(2.0f, 4.0f);
  gl->UseProgram(r->prog_depth);
  mr_uniform_m4(r, r->prog_depth, "u_view_proj", f->light_vp);
  mat4 id = GLM_MAT4_IDENTITY_INIT;
  mr_uniform_m4(r, r->prog_depth, "u_light_vp", id);
  mr_scene_draw_casters(r, list, r->prog_depth);
  gl->UseProgram(0);
  gl->Disable(GL_POLYGON_OFFSET_FILL);
  gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
}
