/* The lit scene: floor, backdrop, the draw list's items and skins, each
 * wearing its material under ambient, sun (with its shadow) and spots;
 * and the same items again as the sun's shadow casters. */
#include <math.h>
#include <string.h>
#include <stdio.h>

#include "render_internal.h"

enum { UNIT_TEXTURE = 0, UNIT_SHADOW = 1, UNIT_BONES = 2 };

static int mirrors(mat4 m) {
  mat3 m3;
  glm_mat4_pick3(m, m3);
  return glm_mat3_det(m3) < 0;
}

static void set_material(mr_render *r, GLuint p, const mr_material_def *m,
                         const mr_gpu_mesh *mesh) {
  mr_uniform_v4(r, p, "u_color", m->base_color);
  mr_uniform_f(r, p, "u_roughness", m->roughness);
  mr_uniform_f(r, p, "u_metallic", m->metallic);
  mr_uniform_v3(r, p, "u_emissive", m->emissive);
  mr_uniform_i(r, p, "u_textured", mesh->texture ? 1 : 0);
  if (mesh->texture) {
    r->gl.ActiveTexture(GL_TEXTURE0 + UNIT_TEXTURE);
    r->gl.BindTexture(GL_TEXTURE_2D, mesh->texture);
  }
}

/* The material worn: the model's k-th, or (k < 0, or none given) the
 * mesh's own. */
static const mr_material_def *worn(const mr_gpu_model *gm, const mr_gpu_mesh *mesh, int k) {
  if (k >= 0 && gm->n_materials > 0) return &gm->materials[k < gm->n_materials ? k : 0];
  return &mesh->material;
}

/* Spot i of the lit program p: at pos, along the unit dir, col (times its
 * intensity), a cone of half-angle angle_deg. */
static void set_spot(mr_render *r, GLuint p, int i, const float *pos, const float *dir,
                     const float *col, double angle_deg) {
  char name[32];
  /* The cone's edge softens over its outer fifth. */
  double a = angle_deg * GLM_PI / 180.0;
  snprintf(name, sizeof name, "u_spot_pos[%d]", i);
  mr_uniform_v3(r, p, name, pos);
  snprintf(name, sizeof name, "u_spot_dir[%d]", i);
  mr_uniform_v3(r, p, name, dir);
  snprintf(name, sizeof name, "u_spot_color[%d]", i);
  mr_uniform_v3(r, p, name, col);
  snprintf(name, sizeof name, "u_spot_cos[%d]", i);
  r->gl.Uniform2f(r->gl.GetUniformLocation(p, name), (float)cos(a), (float)cos(a * 0.8));
}

/* The follow spot in its slot: dark where the frame does not light it. */
static void set_follow_spot(mr_render *r, GLuint p, const mr_frame *f) {
  if (r->follow_slot < 0) return;
  const mr_follow_spot_def *d = &r->stage.follow_spot;
  vec3 col = { 0, 0, 0 }, down = { 0, -1, 0 };
  if (f->follow) glm_vec3_scale((float *)d->color, (float)d->intensity, col);
  set_spot(r, p, r->follow_slot, f->follow_pos, f->follow ? f->follow_dir : down, col,
           d->angle_deg);
}

/* The camera and the lights, on the lit program p (in use). */
static void set_lights(mr_render *r, GLuint p, const mr_frame *f) {
  mr_uniform_m4(r, p, "u_view_proj", (vec4 *)f->view_proj);
  const mr_lights_def *L = &r->stage.lights;
  mr_uniform_v3(r, p, "u_eye", f->eye);
  mr_uniform_v3(r, p, "u_ambient", f->ambient);
  mr_uniform_v3(r, p, "u_sun_dir", f->sun_dir);
  mr_uniform_v3(r, p, "u_sun_color", f->sun_color);
  int n = L->n_spots < 8 ? L->n_spots : 8;
  for (int i = 0; i < n; i++) {
    const mr_spot_def *s = &L->spots[i];
    vec3 pos = { (float)s->position[0], (float)s->position[1], (float)s->position[2] };
    vec3 dir = { (float)(s->target[0] - s->position[0]), (float)(s->target[1] - s->position[1]),
                 (float)(s->target[2] - s->position[2]) };
    glm_vec3_normalize(dir);
    vec3 col;
    glm_vec3_scale((float *)s->color, (float)s->intensity, col);
    set_spot(r, p, i, pos, dir, col, s->angle_deg);
  }
  mr_uniform_v3(r, p, "u_foot_a", r->foot_a);
  mr_uniform_v3(r, p, "u_foot_ab", r->foot_ab);
  mr_uniform_v3(r, p, "u_foot_color", r->foot_color);
  set_follow_spot(r, p, f);
  mr_uniform_i(r, p, "u_shadows", f->shadows ? 1 : 0);
  mr_uniform_m4(r, p, "u_light_vp", (vec4 *)f->light_vp);
  mr_uniform_f(r, p, "u_shadow_texel", r->shadow_size > 0 ? 1.0f / (float)r->shadow_size : 0);
  mr_uniform_i(r, p, "u_texture", UNIT_TEXTURE);
  mr_uniform_i(r, p, "u_shadow_map", UNIT_SHADOW);
  mr_uniform_i(r, p, "u_bones", UNIT_BONES);
  r->gl.ActiveTexture(GL_TEXTURE0 + UNIT_SHADOW);
  r->gl.BindTexture(GL_TEXTURE_2D, r->shadow_tex);
  r->gl.ActiveTexture(GL_TEXTURE0 + UNIT_BONES);
  r->gl.BindTexture(GL_TEXTURE_2D, r->bone_tex);
}

/* An item's model matrix, and the inverse transpose that turns its
 * normals (links stretch along y). A matrix that mirrors turns the
 * winding round: what GL calls a back face is then the outside. */
static void set_model(mr_render *r, GLuint p, mat4 m) {
  mat4 n;
  glm_mat4_inv(m, n);
  glm_mat4_transpose(n);
  mr_uniform_m4(r, p, "u_model", m);
  mr_uniform_m4(r, p, "u_normal", n);
  mr_uniform_i(r, p, "u_mirrored", mirrors(m));
}

/* The backdrop's (or the floor's) program with the frame's lights and
 * its material, in use; its mesh, or NULL when the stage has none. */
static const mr_gpu_mesh *scenery_begin(mr_render *r, const mr_frame *f, bool backdrop) {
  const mr_stage_def *s = &r->stage;
  if (backdrop ? !s->backdrop : !s->floor) return NULL;
  mat4 id = GLM_MAT4_IDENTITY_INIT;
  mr_material_def m = mr_default_material_def();
  m.roughness = 0.9f;
  GLuint p = backdrop ? r->prog_backdrop : r->prog_scenery;
  const mr_gpu_mesh *mesh = backdrop ? &r->backdrop : &r->floor;
  r->gl.UseProgram(p);
  set_lights(r, p, f);
  set_model(r, p, id);
  const float *color = backdrop ? s->backdrop_color : s->floor_color;
  for (int k = 0; k < 3; k++) m.base_color[k] = color[k];
  set_material(r, p, &m, mesh);
  if (!backdrop) {
    mr_set_frame sf;
    mr_set_frame_of(s, &sf);
    mr_uniform_v3(r, p, "u_color2", s->floor_color2);
    mr_uniform_v3(r, p, "u_board_right", sf.right);
    mr_uniform_f(r, p, "u_board", (float)s->board_width);
  }
  return mesh;
}

void mr_scene_draw_set(mr_render *r, const mr_frame *f) {
  if (!mr_set_any(r)) return;
  mat4 id = GLM_MAT4_IDENTITY_INIT;
  GLuint p = r->prog_mesh;
  r->gl.UseProgram(p);
  /* Never in the follow spot's light: the set is kept still, and only
   * the floor and the backdrop are lit again where the spot's pool falls. */
  mr_frame unspotted = *f;
  unspotted.follow = false;
  set_lights(r, p, &unspotted);
  set_model(r, p, id);
  /* Boxes and spheres, closed and wound counter-clockwise outside. */
  r->gl.Enable(GL_CULL_FACE);
  r->gl.CullFace(GL_BACK);
  for (int k = 0; k < MR_SET_PARTS; k++) {
    if (!r->set[k].vao) continue;
    set_material(r, p, &r->set[k].material, &r->set[k]);
    mr_mesh_draw(r, &r->set[k]);
  }
  r->gl.Disable(GL_CULL_FACE);
}

/* The backdrop, then the floor (those asked for), each with its own program, whose shader
 * takes their roughness as given (shader_src.c). The backdrop goes first:
 * the floor runs on behind it (a band of pixels above where they meet),
 * and there it then fails the depth test before it is shaded. */
void mr_scene_draw_scenery(mr_render *r, const mr_frame *f, bool backdrop, bool floor) {
  const mr_gpu_mesh *mesh;
  if (backdrop && (mesh = scenery_begin(r, f, true))) mr_mesh_draw(r, mesh);
  if (floor && (mesh = scenery_begin(r, f, false))) mr_mesh_draw(r, mesh);
}

void mr_scene_draw_scenery_in(mr_render *r, const mr_frame *f, bool backdrop, const int (*rects)[4],
                              int n) {
  const mr_gpu_mesh *mesh = n > 0 ? scenery_begin(r, f, backdrop) : NULL;
  if (!mesh) return;
  r->gl.Enable(GL_SCISSOR_TEST);
  for (int k = 0; k < n; k++) {
    if (rects[k][2] <= 0 || rects[k][3] <= 0) continue;
    r->gl.Scissor(rects[k][0], rects[k][1], rects[k][2], rects[k][3]);
    mr_mesh_draw(r, mesh);
  }
  r->gl.Disable(GL_SCISSOR_TEST);
}

/* A closed mesh wound counter-clockwise seen from outside (every built-in
 * shape, and each model file's mesh found so at load, meshes.c) hides its
 * back faces behind its front ones, so they are culled before they are
 * set up and rasterised (software GL spends a third of a small frame on
 * triangles, and shades a tiny one's whole 4 x 4 block). A model matrix
 * that mirrors turns the winding round. Other model files' meshes, skins
 * and the scenery are seen from both sides: never culled. */
static void cull(mr_render *r, const mr_gpu_mesh *mesh, mat4 m) {
  if (!mesh->closed) {
    r->gl.Disable(GL_CULL_FACE);
    return;
  }
  r->gl.Enable(GL_CULL_FACE);
  r->gl.CullFace(mirrors(m) ? GL_FRONT : GL_BACK);
}

/* The lit pass's scale: pixels a metre at 1 m, half the frame's height
 * over tan(fov / 2). */
static mr_lod_scale lod_scale(const mr_render *r, const mr_frame *f) {
  mr_lod_scale ls = { .k = f->proj[1][1] * 0.5f * (float)r->height };
  glm_vec3_copy((float *)f->eye, ls.eye);
  return ls;
}

/* The items (not skins), with prog; lit sets each mesh's material, and
 * casters draws only the models that cast; a built-in shape at the level
 * its size in pixels (or shadow texels) by ls asks for. */
static void draw_items(mr_render *r, const mr_draw_list *list, GLuint prog, bool lit, bool casters,
                       const mr_lod_scale *ls) {
  for (size_t i = 0; i < list->n_items; i++) {
    const mr_draw_item *it = &list->items[i];
    if (it->model < 0 || (size_t)it->model >= r->n_models) continue;
    const mr_gpu_model *gm = &r->models[it->model];
    if (gm->skinned || (casters && !gm->cast_shadow)) continue;
    mat4 m;
    mr_item_matrix(it, m);
    set_model(r, prog, m);
    for (size_t k = 0; k < gm->n_meshes; k++) {
      if (lit) set_material(r, prog, worn(gm, &gm->meshes[k], it->material), &gm->meshes[k]);
      const mr_gpu_mesh *mesh = mr_mesh_level(gm, k, m, ls);
      cull(r, mesh, m);
      mr_mesh_draw(r, mesh);
    }
  }
  r->gl.Disable(GL_CULL_FACE);
  r->gl.CullFace(GL_BACK);
}

/* The skins, with prog (a skinned program, in use). */
static void draw_skins(mr_render *r, const mr_draw_list *list, GLuint prog, bool lit,
                       bool casters) {
  mr_uniform_i(r, prog, "u_bones", UNIT_BONES);
  for (size_t i = 0; i < list->n_skins; i++) {
    const mr_draw_skin *sk = &list->skins[i];
    if (sk->model < 0 || (size_t)sk->model >= r->n_models) continue;
    const mr_gpu_model *gm = &r->models[sk->model];
    if (!gm->skinned || sk->n_bones < gm->n_bones || !sk->bones) continue;
    if (casters && !gm->cast_shadow) continue;
    r->gl.ActiveTexture(GL_TEXTURE0 + UNIT_BONES);
    mr_bones_upload(r, sk);
    for (size_t k = 0; k < gm->n_meshes; k++) {
      if (lit) set_material(r, prog, worn(gm, &gm->meshes[k], sk->material), &gm->meshes[k]);
      mr_mesh_draw(r, &gm->meshes[k]);
    }
  }
}

/* The items and skins first, then the backdrop and the floor, which they
 * hide in part: a fragment behind what is drawn already fails the depth
 * test before it is shaded. */
/* The kept scenery's shadowed parts, and those the follow spot lights,
 * each surface inside its rectangles. */
static void draw_still_shadows(mr_render *r, const mr_frame *f, const mr_still_rects *still) {
  mr_scene_draw_scenery_in(r, f, true, (const int(*)[4])still->backdrop, still->n_backdrop);
  mr_scene_draw_scenery_in(r, f, false, (const int(*)[4])still->floor, still->n_floor);
  mr_scene_draw_scenery_in(r, f, true, (const int(*)[4])still->spot_backdrop,
                           still->n_spot_backdrop);
  mr_scene_draw_scenery_in(r, f, false, (const int(*)[4])still->spot_floor, still->n_spot_floor);
}

void mr_scene_draw_curtain(mr_render *r, const mr_frame *f) {
  if (!r->curtain.vao || !r->prog_curtain) return;
  mr_frame lit = *f;
  lit.shadows = false;
  lit.follow = false;
  GLuint p = r->prog_curtain;
  r->gl.UseProgram(p);
  set_lights(r, p, &lit);
  mr_material_def m = mr_default_material_def();
  memcpy(m.base_color, r->stage.curtain.color, 3 * sizeof(float));
  m.roughness = 0.85f;
  set_material(r, p, &m, &r->curtain);
  r->gl.Disable(GL_CULL_FACE);
  for (int side = -1; side <= 1; side += 2) {
    mat4 model;
    mr_curtain_matrix(r, f->curtain, side, model);
    set_model(r, p, model);
    mr_mesh_draw(r, &r->curtain);
  }
}

void mr_scene_draw_lit(mr_render *r, const mr_draw_list *list, const mr_frame *f,
                       const mr_still_rects *still) {
  /* The curtain goes first (closed, it hides the rest): drawn whole, or
   * over a kept picture that holds it only when it is open. */
  if (!still || f->curtain < 1) mr_scene_draw_curtain(r, f);
  r->gl.UseProgram(r->prog_mesh);
  set_lights(r, r->prog_mesh, f);
  mr_lod_scale ls = lod_scale(r, f);
  if (list) draw_items(r, list, r->prog_mesh, true, false, &ls);
  if (list && list->n_skins > 0 && r->prog_mesh_skin) {
    r->gl.UseProgram(r->prog_mesh_skin);
    set_lights(r, r->prog_mesh_skin, f);
    draw_skins(r, list, r->prog_mesh_skin, true, false);
  }
  if (!still) {
    mr_scene_draw_set(r, f);
    mr_scene_draw_scenery(r, f, true, true);
  } else {
    draw_still_shadows(r, f, still);
  }
  r->gl.UseProgram(0);
}

void mr_scene_draw_casters(mr_render *r, const mr_draw_list *list, const mr_frame *f) {
  mat4 id = GLM_MAT4_IDENTITY_INIT;
  GLuint progs[2] = { r->prog_depth, r->prog_depth_skin };
  /* The map's texels a metre: the sun's box is square and its view
   * turns only. */
  vec3 row = { f->light_vp[0][0], f->light_vp[1][0], f->light_vp[2][0] };
  mr_lod_scale ls = lod_scale(r, f);
  ls.k_map = glm_vec3_norm(row) * 0.5f * (float)r->shadow_size;
  /* A copy, not a cast of the const frame's matrix: some GCC builds then
   * take the cast pointer for one row and refuse the 64-byte read. */
  mat4 light_vp;
  memcpy(light_vp, f->light_vp, sizeof light_vp);
  for (int k = 0; k < 2; k++) {
    if (!progs[k] || (k == 1 && list->n_skins == 0)) continue;
    r->gl.UseProgram(progs[k]);
    mr_uniform_m4(r, progs[k], "u_view_proj", light_vp);
    mr_uniform_m4(r, progs[k], "u_light_vp", id);
    if (k == 0)
      draw_items(r, list, progs[k], false, true, &ls);
    else
      draw_skins(r, list, progs[k], false, true);
  }
  r->gl.UseProgram(0);
}
