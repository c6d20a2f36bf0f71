/* Day and night (§3.3: "day can turn into night at the turn of a
 * knob"): the day knob sets the sun's direction, its light, the ambient
 * light, the sky's colour, and the stars, which fade in as the sun sets. */
#include <math.h>
#include <stdlib.h>

#include "render_internal.h"

float mr_srgb(float c) {
  if (c <= 0) return 0;
  if (c >= 1) return 1;
  return c < 0.0031308f ? c * 12.92f : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

static float smooth(float e0, float e1, float x) {
  float t = (x - e0) / (e1 - e0);
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  return t * t * (3 - 2 * t);
}

/* The sun goes round once a day: straight down at midnight (t = 0, 1),
 * highest at noon (t = 0.5), rising in -x and setting in +x, and tilted
 * towards the audience (+z) so that shadows fall back towards the
 * backdrop. */
void mr_sky_light(const mr_stage_def *s, double time_of_day, mr_frame *f) {
  const double a = 2 * GLM_PI * time_of_day;
  vec3 dir = { (float)(-0.8 * sin(a)), (float)(-cos(a)), 0.45f };
  glm_vec3_normalize(dir);
  glm_vec3_copy(dir, f->sun_dir);
  float up = smooth(-0.05f, 0.15f, dir[1]);
  f->day = smooth(-0.15f, 0.25f, dir[1]);
  const mr_lights_def *L = &s->lights;
  for (int k = 0; k < 3; k++) {
    f->sun_color[k] = L->sun_color[k] * (float)L->sun_intensity * up;
    f->ambient[k] = L->ambient[k] * (0.2f + 0.8f * f->day);
    f->sky[k] = s->sky_night[k] + (s->sky_day[k] - s->sky_night[k]) * f->day;
  }
  f->shadows = L->shadows && up > 0;
}

int mr_sky_create(mr_render *r, char *msg, size_t msg_size) {
  (void)msg;
  (void)msg_size;
  const mr_stage_def *s = &r->stage;
  if (!s->stars) return 0;
  size_t n = s->n_stars;
  const mr_star *stars = s->star_list;
  if (!stars || n == 0) stars = mr_stage_builtin_stars(&n);
  if (!stars || n == 0) return 0;
  const mr_gl *gl = &r->gl;
  gl->GenVertexArrays(1, &r->star_vao);
  gl->BindVertexArray(r->star_vao);
  gl->GenBuffers(1, &r->star_vbo);
  gl->BindBuffer(GL_ARRAY_BUFFER, r->star_vbo);
  gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * sizeof(mr_star)), stars, GL_STATIC_DRAW);
  gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(mr_star), NULL);
  gl->EnableVertexAttribArray(0);
  gl->VertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, sizeof(mr_star),
                          (const void *)offsetof(mr_star, brightness));
  gl->EnableVertexAttribArray(1);
  gl->BindVertexArray(0);
  r->n_stars = (GLsizei)n;
  return 0;
}

void mr_sky_destroy(mr_render *r) {
  if (r->star_vbo) r->gl.DeleteBuffers(1, &r->star_vbo);
  if (r->star_vao) r->gl.DeleteVertexArrays(1, &r->star_vao);
  r->star_vbo = r->star_vao = 0;
  r->n_stars = 0;
}

void mr_sky_star_points(mr_render *r, GLuint prog, const mr_frame *f, float pad) {
  float night = 1 - f->day;
  if (r->n_stars == 0 || night <= 0) return;
  const mr_gl *gl = &r->gl;
  mr_uniform_m4(r, prog, "u_view_proj", (vec4 *)f->view_proj);
  mr_uniform_v3(r, prog, "u_eye", f->eye);
  mr_uniform_f(r, prog, "u_night", night);
  /* Sized for 720 rows, never under a pixel's worth. */
  float scale = (float)r->height / 720.0f;
  mr_uniform_f(r, prog, "u_point_scale", scale > 1 ? scale : 1);
  mr_uniform_f(r, prog, "u_point_pad", pad);
  /* ES always takes gl_PointSize, and has no such switch. */
  if (!r->gles) gl->Enable(GL_PROGRAM_POINT_SIZE);
  gl->BindVertexArray(r->star_vao);
  gl->DrawArrays(GL_POINTS, 0, r->n_stars);
  gl->BindVertexArray(0);
  if (!r->gles) gl->Disable(GL_PROGRAM_POINT_SIZE);
}

/* After the scene: depth-tested (the floor and backdrop hide them) but
 * not written, added onto the sky. */
void mr_sky_draw_stars(mr_render *r, const mr_frame *f) {
  if (r->n_stars == 0 || f->day >= 1) return;
  const mr_gl *gl = &r->gl;
  gl->UseProgram(r->prog_star);
  gl->Enable(GL_BLEND);
  gl->BlendFunc(GL_SRC_ALPHA, GL_ONE);
  gl->DepthMask(GL_FALSE);
  mr_sky_star_points(r, r->prog_star, f, 0);
  gl->DepthMask(GL_TRUE);
  gl->Disable(GL_BLEND);
  gl->UseProgram(0);
}
