/* The renderer's insides, shared by its files (never by callers). */
#ifndef MR_RENDER_INTERNAL_H
#define MR_RENDER_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <cglm/cglm.h>

#include "gl.h"
#include "mr_render.h"

typedef struct mr_render mr_render;

/* A backend: starts a context (or takes the window's), makes it current,
 * stops. start fills r->gl through its get-proc-address. */
typedef struct mr_backend_ops {
  mr_render_backend kind;
  int (*start)(mr_render *r, const mr_render_def *def, char *msg, size_t msg_size);
  int (*make_current)(mr_render *r);
  void (*stop)(mr_render *r);
} mr_backend_ops;

extern const mr_backend_ops mr_backend_osmesa_ops;
extern const mr_backend_ops mr_backend_egl_ops;
extern const mr_backend_ops mr_backend_window_ops;

/* The window backend's extras (backend_window.c): the size of what the
 * window's context draws into, and the back buffer shown. */
void mr_context_drawable_size(mr_render *r, int *w, int *h);
void mr_context_present(mr_render *r);

/* One mesh on the GPU. Attribute slots: 0 position, 1 normal, 2 uv,
 * 3 bone indices (ivec4), 4 bone weights (vec4). */
typedef struct mr_gpu_mesh {
  GLuint vao, buffers[6];
  GLsizei n_indices;
  GLuint texture;           /* base colour, 0: none */
  mr_material_def material; /* the file's own */
  bool closed;              /* closed, wound counter-clockwise outside: culled */
} mr_gpu_mesh;

typedef struct mr_gpu_model {
  mr_gpu_mesh *meshes;
  size_t n_meshes;
  /* A built-in shape's coarser levels of meshes[0] (shapes.h, level k + 1
   * in lods[k]), drawn where the shape is small (mr_mesh_level). */
  mr_gpu_mesh lods[2];
  int n_lods;
  mr_material_def materials[MR_STAGE_MAX_MATERIALS];
  int n_materials;
  bool skinned, cast_shadow;
  int n_bones;
  float lo[3], hi[3]; /* the meshes' bounds, in the model's own axes (skins: at rest) */
} mr_gpu_model;

/* What one frame is drawn with, worked out once per draw (draw.c). */
typedef struct mr_frame {
  mat4 view, proj, view_proj, light_vp;
  vec3 eye, sun_dir, sun_color, ambient, sky;
  float day;    /* 1 in daylight, 0 at night */
  bool shadows; /* the shadow map holds this frame's sun */
  /* The follow spot (the draw list's), lit where follow is set: never in
   * the kept scenery nor on the curtain (curtain.c says why). */
  bool follow;
  vec3 follow_pos, follow_dir;
  float curtain; /* the curtain's openness, 0 closed to 1 open */
} mr_frame;

struct mr_text; /* text.c */

/* The theater's set (set.c): its meshes, one per material. */
enum {
  MR_SET_ARCH,
  MR_SET_TRIM,
  MR_SET_DARK,
  MR_SET_SKIRT,
  MR_SET_LAMP,
  MR_SET_WOOD,
  MR_SET_PARTS
};

/* Buffers a frame's drawing works in, kept by the renderer and grown as a
 * frame needs them, so that frames after the first allocate nothing: a
 * show may run for hours, and memory running out in its middle would
 * take the strings off the picture. */
enum {
  MR_SCRATCH_BONES,
  MR_SCRATCH_LINES,
  MR_SCRATCH_POINTS,
  MR_SCRATCH_POLYGON,
  MR_SCRATCH_COUNT
};
typedef struct mr_scratch {
  void *p;
  size_t size;
} mr_scratch;

struct mr_render {
  mr_render_backend backend;
  const mr_backend_ops *ops;
  void *bk; /* the backend's own state */
  mr_gl gl;
  bool gles;           /* the context is OpenGL ES 3.x, set by the backend */
  char gl_version[32]; /* "OpenGL 4.5 core", "OpenGL ES 3.2" */
  int width, height, samples;
  bool software;   /* GL draws in software (llvmpipe, softpipe, swrast) */
  bool smooth;     /* one sample, and the edge-smoothing pass (post.c) */
  int shadow_taps; /* the shadow filter's reads, 1, 4 or 9 */
  char description[256], quality[128];
  mr_stage_def stage; /* a copy; its pointers are not used after create */
  /* The frame's targets (fbo.c): multisampled, then resolved; or, when
   * smoothed, one sample into a texture, then the post pass. */
  GLuint fbo_ms, rb_color_ms, rb_depth_ms, fbo_out, rb_color_out, tex_frame, post_vao, post_vbo;
  bool drawn;
  /* The still scenery, kept (still.c). */
  GLuint still_fbo, still_color, still_depth;
  float still_key[32], still_last[32]; /* what is kept; the last frame's */
  bool still_kept;
  uint8_t *read_buf; /* the read back's staging buffer (fbo.c) */
  size_t read_size;
  struct mr_scratch *scratch; /* MR_SCRATCH_COUNT of them (mr_render_scratch) */
  /* Programs (shaders.c). */
  GLuint prog_mesh, prog_depth, prog_line, prog_star, prog_text, prog_smooth;
  GLuint prog_mesh_skin, prog_depth_skin; /* 0 when the stage has no freeform model */
  GLuint prog_scenery;                    /* the floor's lit program (its checkerboard) */
  GLuint prog_backdrop;                   /* the backdrop's */
  GLuint prog_smooth_stars;               /* the smoothing over the stars (post.c) */
  GLuint prog_curtain;                    /* the items' without spots (curtain.c); 0: none */
  /* The sun's shadow map (shadow.c). */
  GLuint shadow_fbo, shadow_tex;
  int shadow_size;
  float *shadow_key; /* what the map was last drawn for (shadow.c) */
  size_t shadow_key_len;
  bool shadow_drawn;
  /* Meshes (meshes.c). */
  mr_gpu_model *models;
  size_t n_models;
  mr_gpu_mesh floor, backdrop;
  GLuint bone_tex;
  /* The theater's set (set.c): meshes in world coordinates, each wearing
   * its own material; the footlights' row (a line light) and colour. */
  mr_gpu_mesh set[MR_SET_PARTS];
  float foot_a[3], foot_ab[3], foot_color[3];
  /* The front curtain's half (curtain.c), and the follow spot's slot
   * among the spots (-1: none). */
  mr_gpu_mesh curtain;
  mr_curtain_place curtain_place;
  int follow_slot;
  /* Stars and lines (sky.c, lines.c). */
  GLuint star_vao, star_vbo, line_vao, line_vbo;
  GLsizei n_stars;
  struct mr_text *text;
};

/* glapi.c: the description and short version of the context. */
void mr_gl_describe(mr_render *r);

/* fbo.c */
int mr_fbo_create(mr_render *r, char *msg, size_t msg_size);
void mr_fbo_destroy(mr_render *r);
void mr_fbo_bind_draw(mr_render *r);
/* Resolves (or smooths) the frame into the output framebuffer, and
 * leaves that bound for what is drawn over it (the on-screen text). */
void mr_fbo_resolve(mr_render *r, const mr_draw_list *list, const mr_frame *f);
int mr_fbo_read_rgb(mr_render *r, uint8_t *rgb); /* -1: out of memory */
/* Window: the last frame blitted into the window's back buffer. */
void mr_fbo_blit_to_window(mr_render *r, int w, int h);

/* post.c: the frame, already copied into the bound output framebuffer,
 * smoothed at its edges where the draw list's models and the scenery's
 * outlines are (at most MR_POST_MAX_VERTS vertices of regions). */
#define MR_POST_MAX_VERTS 96
void mr_post_smooth(mr_render *r, const mr_draw_list *list, const mr_frame *f);

/* shaders.c */
int mr_shaders_create(mr_render *r, char *msg, size_t msg_size);
void mr_shaders_destroy(mr_render *r);
/* Uniform setters by name, on the program in use. */
void mr_uniform_i(mr_render *r, GLuint prog, const char *name, int v);
void mr_uniform_f(mr_render *r, GLuint prog, const char *name, float v);
void mr_uniform_v3(mr_render *r, GLuint prog, const char *name, const float *v);
void mr_uniform_v4(mr_render *r, GLuint prog, const char *name, const float *v);
void mr_uniform_m4(mr_render *r, GLuint prog, const char *name, mat4 m);

/* meshes.c */
#define MR_BACKDROP_HALF_HEIGHT 0.8f /* the backdrop is 1.6 m tall */
int mr_meshes_create(mr_render *r, const mr_stage_def *stage, const char *scene_path, char *msg,
                     size_t msg_size, mr_render_status *status);
void mr_meshes_destroy(mr_render *r);
void mr_mesh_draw(mr_render *r, const mr_gpu_mesh *m);
/* How many pixels a metre covers where a model is drawn: k at 1 m from
 * the eye, falling as the distance grows; and, drawn into the shadow map,
 * no more than its texels a metre, k_map (0: not). */
typedef struct mr_lod_scale {
  vec3 eye;
  float k, k_map;
} mr_lod_scale;
/* Mesh k of gm as drawn with model matrix m: for a built-in shape's one
 * mesh, the coarsest level whose outline stays within half a pixel of the
 * round shape's at that size; otherwise meshes[k]. */
const mr_gpu_mesh *mr_mesh_level(const mr_gpu_model *gm, size_t k, mat4 m, const mr_lod_scale *s);
/* The model matrix of a draw item: scale, then pose. */
void mr_item_matrix(const mr_draw_item *item, mat4 out);
/* A pose as a matrix (a skin's bone: rest to now). */
void mr_pose_matrix(const mr_pose *p, mat4 out);
/* Uploads a skin's bone matrices into the bone texture. */
void mr_bones_upload(mr_render *r, const mr_draw_skin *skin);

/* A mesh made here (the set's, the curtain's) uploaded (no bones), and
 * freed (the meshes free them all). */
struct mr_mesh;
void mr_mesh_upload(mr_render *r, mr_gpu_mesh *g, const struct mr_mesh *m);
void mr_mesh_free(mr_render *r, mr_gpu_mesh *g);

/* set.c: the theater's set. Its axes: right (the audience's right),
 * front (towards the audience), both level, and the origin on the floor
 * in the arch's plane at the opening's middle; the opening width x
 * height, the posts' width and the header's height; how far the backdrop
 * stands behind the arch; edge: the stage has a front edge (the boards
 * end MR_SET_APRON m in front of the arch, mr_stage.h). */
typedef struct mr_set_frame {
  float origin[3], right[3], front[3];
  float width, height, post, header, deep;
  bool edge;
} mr_set_frame;
void mr_set_frame_of(const mr_stage_def *s, mr_set_frame *f);
/* A point in the set's axes, in the world. */
void mr_set_to_world(const mr_set_frame *f, const float p[3], float out[3]);
int mr_set_create(mr_render *r, char *msg, size_t msg_size);
void mr_set_destroy(mr_render *r);
/* True when the stage has any part of the set. */
bool mr_set_any(const mr_render *r);
/* The floor's outline, the square of half-side h cut at the stage's
 * front edge: its corners' x and z, counter-clockwise from above; how
 * many (3 to 5). */
size_t mr_set_floor_outline(const mr_stage_def *s, float h, float xz[5][2]);

/* still.c: the sky, the backdrop and the floor, unshadowed, kept while
 * the camera and the sun stay (software GL, one sample). */
/* Where on screen shadows can fall on the backdrop and on the floor: up
 * to MR_STILL_BANDS rectangles (x, y, w, h) each, bands of rows. */
#define MR_STILL_BANDS 8
typedef struct mr_still_rects {
  int backdrop[MR_STILL_BANDS][4], floor[MR_STILL_BANDS][4];
  int n_backdrop, n_floor;
  /* Where the follow spot's cone meets each surface (it moves, so the
   * kept scenery is drawn without it). */
  int spot_backdrop[MR_STILL_BANDS][4], spot_floor[MR_STILL_BANDS][4];
  int n_spot_backdrop, n_spot_floor;
} mr_still_rects;
int mr_still_create(mr_render *r, char *msg, size_t msg_size);
void mr_still_destroy(mr_render *r);
/* Copies the kept scenery (drawn again first when the camera or the sun
 * moved) into the drawing framebuffer and leaves that bound; out says
 * where the shadows can fall. False when nothing is kept: the frame is
 * cleared and drawn whole. */
bool mr_still_draw(mr_render *r, const mr_draw_list *list, const mr_frame *f, mr_still_rects *out);

/* scene.c: the lit scene, and the shadow pass's casters. With still (the
 * scenery kept), the backdrop and the floor are drawn again only inside
 * its rectangles. */
void mr_scene_draw_lit(mr_render *r, const mr_draw_list *list, const mr_frame *f,
                       const mr_still_rects *still);
/* The backdrop and (or) the floor, lit. */
void mr_scene_draw_scenery(mr_render *r, const mr_frame *f, bool backdrop, bool floor);
/* The theater's set, lit (no shadows fall on it). */
void mr_scene_draw_set(mr_render *r, const mr_frame *f);
/* The backdrop (or the floor), lit, only inside each of n rectangles. */
void mr_scene_draw_scenery_in(mr_render *r, const mr_frame *f, bool backdrop, const int (*rects)[4],
                              int n);
/* The casters into the shadow map, with the shadow programs, seen
 * through light_vp. */
void mr_scene_draw_casters(mr_render *r, const mr_draw_list *list, const mr_frame *f);
/* The front curtain at f->curtain's openness, lit (no shadow, no follow
 * spot); nothing when the stage has none. */
void mr_scene_draw_curtain(mr_render *r, const mr_frame *f);

/* curtain.c: the curtain's half as a pleated strip, made at create (0,
 * or -1 when memory runs out); the model matrix of a half (side -1 left,
 * +1 right) at an openness; the follow spot's slot and its light in the
 * frame. */
int mr_curtain_create(mr_render *r, const mr_stage_def *stage);
void mr_curtain_matrix(const mr_render *r, float openness, int side, mat4 out);
void mr_follow_spot_frame(const mr_render *r, const mr_draw_list *list, mr_frame *f);

/* shadow.c */
int mr_shadow_create(mr_render *r, char *msg, size_t msg_size);
void mr_shadow_destroy(mr_render *r);
void mr_shadow_draw(mr_render *r, const mr_draw_list *list, mr_frame *f);

/* sky.c */
void mr_sky_light(const mr_stage_def *s, double time_of_day, mr_frame *f);
int mr_sky_create(mr_render *r, char *msg, size_t msg_size);
void mr_sky_destroy(mr_render *r);
void mr_sky_draw_stars(mr_render *r, const mr_frame *f);
/* The stars as points with prog (in use, taking the star shader's
 * uniforms), pad pixels wider than they are drawn; nothing by day. */
void mr_sky_star_points(mr_render *r, GLuint prog, const mr_frame *f, float pad);
/* Linear to sRGB, as the shaders do it. */
float mr_srgb(float linear);

/* lines.c: the rigging's lines, MR_LINE_WIDTH_PX pixels wide with soft
 * edges, depth-tested, blended over the frame. */
#define MR_LINE_WIDTH_PX 1.0f
int mr_lines_create(mr_render *r);
void mr_lines_destroy(mr_render *r);
void mr_lines_draw(mr_render *r, const mr_draw_line *lines, size_t n, const mr_frame *f);

/* text.c */
int mr_text_create(mr_render *r, const char *font_path, char *msg, size_t msg_size);
void mr_text_destroy(mr_render *r);
void mr_text_draw(mr_render *r, const char *const *lines, size_t n);

/* For tests of the window path: the last frame as the window shows it
 * (blitted into its back buffer and read from there), RGB, top row first,
 * at the window's drawable size (w, h). -1 when not a window, when size is
 * too small, or when out of memory. */
int mr_render_read_window_rgb(mr_render *r, uint8_t *rgb, size_t size, int *w, int *h);

/* Scratch k of r with room for bytes, what it held kept (render.c): NULL
 * when memory runs out, the scratch then as it was. Not the renderer's
 * state, which is why r may be const. */
void *mr_render_scratch(const mr_render *r, int k, size_t bytes);

#endif
