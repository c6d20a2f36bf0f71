/* The renderer's programs, compiled and linked once at create, and
 * uniforms set by name. */
#include <stdio.h>

#include "render_internal.h"
#include "shader_src.h"

/* Each shader is one body (shader_src.c) in the subset GLSL 3.30 core and
 * GLSL ES 3.00 share, after a header for the context's language: its
 * #version line and, for ES, precision statements. ES gives no default
 * precision for float in fragment shaders nor for sampler2DShadow at all,
 * and only lowp for sampler2D; highp everywhere keeps the bones (floats
 * read by texelFetch), the shadow depths and the lighting as exact as on
 * the desktop, and every ES 3.0 fragment shader has highp. */
static const char glsl_core[] = "#version 330 core\n";
static const char glsl_es[] = "#version 300 es\n"
                              "precision highp float;\n"
                              "precision highp int;\n"
                              "precision highp sampler2D;\n"
                              "precision highp sampler2DShadow;\n";

static GLuint compile(mr_render *r, GLenum kind, const char *src, const char *what, char *msg,
                      size_t msg_size) {
  const mr_gl *gl = &r->gl;
  GLuint s = gl->CreateShader(kind);
  const char *parts[2] = { r->gles ? glsl_es : glsl_core, src };
  gl->ShaderSource(s, 2, parts, NULL);
  gl->CompileShader(s);
  GLint ok = 0;
  gl->GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (ok) return s;
  char log[512] = "";
  gl->GetShaderInfoLog(s, sizeof log, NULL, log);
  snprintf(msg, msg_size, "the %s shader does not compile: %s", what, log);
  gl->DeleteShader(s);
  return 0;
}

static GLuint program(mr_render *r, const char *vs_src, const char *fs_src, const char *what,
                      char *msg, size_t msg_size) {
  const mr_gl *gl = &r->gl;
  GLuint vs = compile(r, GL_VERTEX_SHADER, vs_src, what, msg, msg_size);
  if (!vs) return 0;
  GLuint fs = compile(r, GL_FRAGMENT_SHADER, fs_src, what, msg, msg_size);
  if (!fs) {
    gl->DeleteShader(vs);
    return 0;
  }
  GLuint p = gl->CreateProgram();
  gl->AttachShader(p, vs);
  gl->AttachShader(p, fs);
  gl->LinkProgram(p);
  gl->DeleteShader(vs);
  gl->DeleteShader(fs);
  GLint ok = 0;
  gl->GetProgramiv(p, GL_LINK_STATUS, &ok);
  if (ok) return p;
  char log[512] = "";
  gl->GetProgramInfoLog(p, sizeof log, NULL, log);
  snprintf(msg, msg_size, "the %s program does not link: %s", what, log);
  gl->DeleteProgram(p);
  return 0;
}

static bool has_skins(const mr_stage_def *s) {
  for (size_t i = 0; i < s->n_models; i++)
    if (s->models && s->models[i].display == MR_DISPLAY_FREEFORM) return true;
  return false;
}

/* The mesh programs, lit and shadow, each for items and (when the stage
 * has a freeform model) for skins, and the lit one for the scenery. The stage's spot count and the shadow
 * filter are constants of the lit shader, as skinning is of the vertex
 * shader (shader_src.c says why). */
static int mesh_programs(mr_render *r, char *msg, size_t msg_size) {
  int n_spots = r->stage.lights.n_spots < 8 ? r->stage.lights.n_spots : 8;
  n_spots = n_spots > 0 ? n_spots : 0;
  const int foot = r->stage.footlights, taps = r->shadow_taps;
  /* The follow spot takes the next slot, when one is free. */
  r->follow_slot = r->stage.follow_spot.show && n_spots < 8 ? n_spots++ : -1;
  char vs[4096], vs_skin[4096], fs[12288], fs_floor[12288], fs_backdrop[12288];
  if (mr_src_mesh_vs_make(vs, sizeof vs, 0) != 0 ||
      mr_src_mesh_vs_make(vs_skin, sizeof vs_skin, 1) != 0 ||
      mr_src_mesh_fs_make(fs, sizeof fs, n_spots, taps, MR_SRC_ITEMS, foot) != 0 ||
      mr_src_mesh_fs_make(fs_floor, sizeof fs_floor, n_spots, taps, MR_SRC_FLOOR, foot) != 0 ||
      mr_src_mesh_fs_make(fs_backdrop, sizeof fs_backdrop, n_spots, taps, MR_SRC_BACKDROP, foot) !=
          0) {
    snprintf(msg, msg_size, "a mesh shader's source does not fit its buffer");
    return -1;
  }
  r->prog_mesh = program(r, vs, fs, "mesh", msg, msg_size);
  if (!r->prog_mesh) return -1;
  r->prog_scenery = program(r, vs, fs_floor, "floor", msg, msg_size);
  if (!r->prog_scenery) return -1;
  r->prog_backdrop = program(r, vs, fs_backdrop, "backdrop", msg, msg_size);
  if (!r->prog_backdrop) return -1;
  r->prog_depth = program(r, vs, mr_src_depth_fs, "shadow", msg, msg_size);
  if (!r->prog_depth) return -1;
  /* The curtain: the items' shader without spots (curtain.c says why). */
  if (r->stage.curtain.show) {
    if (mr_src_mesh_fs_make(fs, sizeof fs, 0, 1, MR_SRC_ITEMS, foot) != 0) {
      snprintf(msg, msg_size, "a mesh shader's source does not fit its buffer");
      return -1;
    }
    r->prog_curtain = program(r, vs, fs, "curtain", msg, msg_size);
    if (!r->prog_curtain) return -1;
  }
  if (!has_skins(&r->stage)) return 0;
  r->prog_mesh_skin = program(r, vs_skin, fs, "skinned mesh", msg, msg_size);
  if (!r->prog_mesh_skin) return -1;
  r->prog_depth_skin = program(r, vs_skin, mr_src_depth_fs, "skinned shadow", msg, msg_size);
  return r->prog_depth_skin ? 0 : -1;
}

int mr_shaders_create(mr_render *r, char *msg, size_t msg_size) {
  if (mesh_programs(r, msg, msg_size) != 0) return -1;
  r->prog_line = program(r, mr_src_line_vs, mr_src_line_fs, "line", msg, msg_size);
  if (!r->prog_line) return -1;
  r->prog_star = program(r, mr_src_star_vs, mr_src_star_fs, "star", msg, msg_size);
  if (!r->prog_star) return -1;
  r->prog_text = program(r, mr_src_text_vs, mr_src_text_fs, "text", msg, msg_size);
  if (!r->prog_text) return -1;
  if (!r->smooth) return 0;
  r->prog_smooth = program(r, mr_src_post_vs, mr_src_smooth_fs, "edge smoothing", msg, msg_size);
  if (!r->prog_smooth) return -1;
  r->prog_smooth_stars =
      program(r, mr_src_star_vs, mr_src_smooth_fs, "edge smoothing of stars", msg, msg_size);
  return r->prog_smooth_stars ? 0 : -1;
}

void mr_shaders_destroy(mr_render *r) {
  GLuint *progs[] = { &r->prog_mesh,   &r->prog_scenery,      &r->prog_backdrop,
                      &r->prog_depth,  &r->prog_mesh_skin,    &r->prog_depth_skin,
                      &r->prog_line,   &r->prog_star,         &r->prog_text,
                      &r->prog_smooth, &r->prog_smooth_stars, &r->prog_curtain };
  for (size_t i = 0; i < sizeof progs / sizeof progs[0]; i++) {
    if (*progs[i]) r->gl.DeleteProgram(*progs[i]);
    *progs[i] = 0;
  }
}

void mr_uniform_i(mr_render *r, GLuint prog, const char *name, int v) {
  r->gl.Uniform1i(r->gl.GetUniformLocation(prog, name), v);
}

void mr_uniform_f(mr_render *r, GLuint prog, const char *name, float v) {
  r->gl.Uniform1f(r->gl.GetUniformLocation(prog, name), v);
}

void mr_uniform_v3(mr_render *r, GLuint prog, const char *name, const float *v) {
  r->gl.Uniform3fv(r->gl.GetUniformLocation(prog, name), 1, v);
}

void mr_uniform_v4(mr_render *r, GLuint prog, const char *name, const float *v) {
  r->gl.Uniform4fv(r->gl.GetUniformLocation(prog, name), 1, v);
}

void mr_uniform_m4(mr_render *r, GLuint prog, const char *name, mat4 m) {
  r->gl.UniformMatrix4fv(r->gl.GetUniformLocation(prog, name), 1, GL_FALSE, (const GLfloat *)m);
}
