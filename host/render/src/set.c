/* The theater's set as meshes made here, in C, from boxes and spheres
 * (the built-in sphere of shapes.c for the lamps): a proscenium arch of
 * dark red with gold edging in a dark front wall, the stage's front
 * below the boards, two pairs of black legs and borders (the wings),
 * footlights in a trough at the stage's front edge, and, when asked, the
 * puppeteer's bridge behind and above the backdrop. Each material's
 * boxes are one mesh, in world coordinates, so the set is a handful of
 * draws; it is still scenery, drawn into the kept picture (still.c) and
 * not again while the camera stays.
 *
 * Sizes, in the set's own axes (x the audience's right, y up, z towards
 * the audience; the origin on the floor, in the arch's plane, at the
 * opening's middle): the opening W x H, the posts 0.1 W + 0.12 wide, the
 * header 0.14 H + 0.12 tall, the arch APRON in front of the stage's front
 * edge. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "render_internal.h"
#include "shapes.h"

#define ARCH_DEPTH   0.12f
#define TRIM         0.05f /* the gold edging's width */
#define LAMP_RADIUS  0.028f
#define LAMP_HEIGHT  0.048f /* its middle above the boards: half over the lip */
#define LAMP_SPACING 0.24f

static const float DEG = 3.14159265f / 180.0f;

void mr_set_frame_of(const mr_stage_def *s, mr_set_frame *f) {
  const float az = (float)s->facing_deg * DEG;
  f->right[0] = cosf(az), f->right[1] = 0, f->right[2] = -sinf(az);
  f->front[0] = sinf(az), f->front[1] = 0, f->front[2] = cosf(az);
  f->width = (float)(s->set_width > 0 ? s->set_width : MR_SET_WIDTH);
  f->height = (float)(s->set_height > 0 ? s->set_height : MR_SET_HEIGHT);
  const float plane = (float)(s->set_front > 0 ? s->set_front : MR_SET_FRONT),
              mid = (float)s->set_middle;
  for (int k = 0; k < 3; k++) f->origin[k] = mid * f->right[k] + plane * f->front[k];
  f->origin[1] = (float)s->floor_height;
  f->post = 0.1f * f->width + 0.12f;
  f->header = 0.14f * f->height + 0.12f;
  /* How far the backdrop stands behind the arch (its plane is z = -d in
   * the world; the set turns with facing, so along the front axis). */
  f->deep = s->backdrop ? plane + (float)s->backdrop_distance * f->front[2] : 2.5f;
  if (f->deep < 0.6f) f->deep = 0.6f;
  f->edge = s->proscenium || s->footlights;
}

void mr_set_to_world(const mr_set_frame *f, const float p[3], float out[3]) {
  for (int k = 0; k < 3; k++)
    out[k] = f->origin[k] + p[0] * f->right[k] + p[2] * f->front[k] + (k == 1 ? p[1] : 0);
}

/* A growing mesh of one material. */
typedef struct batch {
  float *pos, *nor;
  uint32_t *idx;
  size_t nv, ni, cap_v, cap_i;
  bool failed;
} batch;

static bool grow(batch *b, size_t nv, size_t ni) {
  if (b->failed) return false;
  if (b->nv + nv > b->cap_v) {
    size_t cap = (b->cap_v + nv) * 2;
    float *p = realloc(b->pos, 3 * cap * sizeof *p),
          *n = p ? realloc(b->nor, 3 * cap * sizeof *n) : NULL;
    if (p) b->pos = p;
    if (n) b->nor = n;
    if (!p || !n) return !(b->failed = true);
    b->cap_v = cap;
  }
  if (b->ni + ni > b->cap_i) {
    size_t cap = (b->cap_i + ni) * 2;
    uint32_t *i = realloc(b->idx, cap * sizeof *i);
    if (!i) return !(b->failed = true);
    b->idx = i, b->cap_i = cap;
  }
  return true;
}

static void add_vertex(batch *b, const mr_set_frame *f, const float p[3], const float n[3]) {
  float w[3], o[3] = { 0, 0, 0 };
  mr_set_to_world(f, p, w);
  float origin[3];
  mr_set_to_world(f, o, origin);
  float nn[3] = { n[0], n[1], n[2] }, wn[3];
  mr_set_to_world(f, nn, wn);
  for (int k = 0; k < 3; k++) {
    b->pos[3 * b->nv + (size_t)k] = w[k];
    b->nor[3 * b->nv + (size_t)k] = wn[k] - origin[k];
  }
  b->nv++;
}

/* A box from lo to hi in the set's axes: 6 faces of 4 vertices, wound
 * counter-clockwise seen from outside (culled from behind). */
static void add_box(batch *b, const mr_set_frame *f, float x0, float y0, float z0, float x1,
                    float y1, float z1) {
  if (!grow(b, 24, 36)) return;
  const float lo[3] = { x0, y0, z0 }, hi[3] = { x1, y1, z1 };
  for (int axis = 0; axis < 3; axis++) {
    for (int side = 0; side < 2; side++) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      float n[3] = { 0, 0, 0 };
      n[axis] = side ? 1.0f : -1.0f;
      uint32_t base = (uint32_t)b->nv;
      for (int c = 0; c < 4; c++) {
        float p[3];
        p[axis] = side ? hi[axis] : lo[axis];
        p[u] = (c == 1 || c == 2) ? hi[u] : lo[u];
        p[v] = (c >= 2) ? hi[v] : lo[v];
        add_vertex(b, f, p, n);
      }
      /* (u, v) turns counter-clockwise about +axis: keep it for the +
       * side, turn it round for the - side. */
      const uint32_t order[2][6] = { { 0, 2, 1, 0, 3, 2 }, { 0, 1, 2, 0, 2, 3 } };
      for (int k = 0; k < 6; k++) b->idx[b->ni++] = base + order[side][k];
    }
  }
}

/* A sphere of radius rad about c, from the built-in shape's coarsest
 * level (a lamp a few pixels across). */
static void add_sphere(batch *b, const mr_set_frame *f, const mr_mesh *unit, const float c[3],
                       float rad) {
  if (!grow(b, unit->n_vertices, unit->n_indices)) return;
  uint32_t base = (uint32_t)b->nv;
  for (size_t v = 0; v < unit->n_vertices; v++) {
    float p[3];
    for (int k = 0; k < 3; k++) p[k] = c[k] + 2 * rad * unit->positions[3 * v + (size_t)k];
    add_vertex(b, f, p, &unit->normals[3 * v]);
  }
  for (size_t i = 0; i < unit->n_indices; i++) b->idx[b->ni++] = base + unit->indices[i];
}

static void arch(batch *red, batch *gold, batch *dark, const mr_set_frame *f) {
  const float w = f->width / 2, h = f->height, p = f->post, top = h + f->header, d = ARCH_DEPTH;
  add_box(red, f, -w - p, 0, -d, -w, top, 0);
  add_box(red, f, w, 0, -d, w + p, top, 0);
  add_box(red, f, -w, h, -d, w, top, 0);
  /* Gold edging about the opening and along the arch's outside. */
  add_box(gold, f, -w - TRIM, 0, 0, -w, h + TRIM, 0.015f);
  add_box(gold, f, w, 0, 0, w + TRIM, h + TRIM, 0.015f);
  add_box(gold, f, -w - TRIM, h, 0, w + TRIM, h + TRIM, 0.015f);
  add_box(gold, f, -w - p, 0, 0, -w - p + 0.6f * TRIM, top, 0.012f);
  add_box(gold, f, w + p - 0.6f * TRIM, 0, 0, w + p, top, 0.012f);
  add_box(gold, f, -w - p, top - 0.6f * TRIM, 0, w + p, top, 0.012f);
  /* The house's front wall about the arch. */
  const float far = w + p + 6, high = top + 4;
  add_box(dark, f, -far, -3, -d, -w - p, high, -d + 0.02f);
  add_box(dark, f, w + p, -3, -d, far, high, -d + 0.02f);
  add_box(dark, f, -w - p, top, -d, w + p, high, -d + 0.02f);
}

/* The stage's front below the boards, from the arch to its front edge. */
static void stage_front(batch *skirt, const mr_set_frame *f, float floor_half) {
  const float w = f->width / 2 + f->post + 2 * floor_half;
  add_box(skirt, f, -w, -3, -ARCH_DEPTH, w, -0.002f, MR_SET_APRON);
}

/* Where the scene's own camera (the audience's) stands, in the set's
 * axes. */
static void eye_in_set(const mr_stage_def *s, const mr_set_frame *f, float e[3]) {
  mr_orbit o = mr_orbit_of_stage(s);
  double w[3];
  mr_orbit_eye(&o, w);
  float d[3] = { (float)w[0] - f->origin[0], (float)w[1] - f->origin[1],
                 (float)w[2] - f->origin[2] };
  e[0] = d[0] * f->right[0] + d[2] * f->right[2];
  e[1] = d[1];
  e[2] = d[0] * f->front[0] + d[2] * f->front[2];
}

/* Legs (tall flats either side) and borders (across the top), two pairs
 * between the arch and the backdrop. Each is set on the audience's
 * sightline past a line a little inside the opening's edge (as a theater
 * sets its masking), so that from the seats they show as a dark band
 * inside the arch and do not narrow the stage into a tunnel. They never
 * hide a puppet: a scene keeps the show within (w - 0.25) / 1.2 of the
 * opening's middle (half-width w) and 0.25 m under its top (scene_set.c),
 * and a flat stands no nearer the middle than 0.85 w, nor lower than
 * 0.2 m under the top; a line from the eye to a point of the show stays
 * between the two, inside those. */
static void wings(batch *black, const mr_stage_def *s, const mr_set_frame *f) {
  const float w = f->width / 2, h = f->height, top = f->height + f->header;
  float e[3];
  eye_in_set(s, f, e);
  for (int k = 1; k <= 2; k++) {
    const float z = -f->deep * (k == 1 ? 0.3f : 0.62f), t = 0.03f;
    /* How much larger the opening looks there than in the arch's plane
     * (1 with the eye behind the arch or level with it). */
    const float grow = e[2] > 0.3f ? (e[2] - z) / e[2] : 1.0f;
    const float in_r = fmaxf(e[0] + (0.85f * w - e[0]) * grow, 0.85f * w);
    const float in_l = fmaxf(-e[0] + (0.85f * w + e[0]) * grow, 0.85f * w);
    const float low = fmaxf(e[1] + (h - 0.15f - e[1]) * grow, h - 0.2f);
    const float out = fmaxf(in_l, in_r) + 1.2f;
    add_box(black, f, -out, 0, z - t, -in_l, fmaxf(top, low + 0.5f), z);
    add_box(black, f, in_r, 0, z - t, out, fmaxf(top, low + 0.5f), z);
    add_box(black, f, -out, low, z - t, out, low + 0.6f + top - h, z);
  }
}

/* Lamps along the front edge, behind a low trough; and where their light
 * comes from (a row just above them). */
static void footlights(mr_render *r, batch *lamp, batch *black, const mr_set_frame *f,
                       const mr_mesh *unit) {
  const float w = f->width / 2 - 0.1f, z = MR_SET_APRON - 0.09f;
  add_box(black, f, -w - 0.05f, 0, MR_SET_APRON - 0.04f, w + 0.05f, 0.04f, MR_SET_APRON);
  int n = (int)floorf(2 * w / LAMP_SPACING) + 1;
  for (int i = 0; i < n; i++) {
    const float c[3] = { -w + (float)i * 2 * w / (float)(n > 1 ? n - 1 : 1), LAMP_HEIGHT, z };
    add_sphere(lamp, f, unit, c, LAMP_RADIUS);
  }
  const float a[3] = { -w, 0.06f, z + 0.05f }, b[3] = { w, 0.06f, z + 0.05f };
  float wa[3], wb[3];
  mr_set_to_world(f, a, wa);
  mr_set_to_world(f, b, wb);
  const mr_stage_def *s = &r->stage;
  for (int k = 0; k < 3; k++) {
    r->foot_a[k] = wa[k];
    r->foot_ab[k] = wb[k] - wa[k];
    r->foot_color[k] = s->footlight_color[k] * (float)s->footlight_intensity;
  }
}

/* The puppeteer's bridge: a deck on posts behind the backdrop, above its
 * top, with a rail the puppeteer leans on. */
static void bridge(batch *wood, const mr_set_frame *f, float backdrop_top) {
  const float w = f->width / 2 + f->post, z0 = -f->deep - 0.95f, z1 = -f->deep - 0.15f;
  const float y = backdrop_top + 0.35f;
  add_box(wood, f, -w, y - 0.07f, z0, w, y, z1);
  for (int i = -1; i <= 1; i += 2)
    for (int j = 0; j < 2; j++) {
      const float x = i * (w - 0.05f), zz = j ? z1 - 0.05f : z0 + 0.05f;
      add_box(wood, f, x - 0.04f, 0, zz - 0.04f, x + 0.04f, y - 0.07f, zz + 0.04f);
    }
  add_box(wood, f, -w, y + 0.95f, z1 - 0.06f, w, y + 1.0f, z1);
  for (float x = -w; x <= w + 1e-3f; x += (2 * w) / 6)
    add_box(wood, f, x - 0.02f, y, z1 - 0.05f, x + 0.02f, y + 0.95f, z1 - 0.01f);
}

static mr_material_def material(const float *rgb, float roughness, float metallic) {
  mr_material_def m = mr_default_material_def();
  for (int k = 0; k < 3; k++) m.base_color[k] = rgb[k];
  m.roughness = roughness;
  m.metallic = metallic;
  return m;
}

static void upload(mr_render *r, int part, batch *b, mr_material_def m) {
  if (b->nv == 0 || b->failed) return;
  mr_mesh mesh = mr_mesh_of(b->pos, b->nor, b->nv, b->idx, b->ni, m);
  mr_mesh_upload(r, &r->set[part], &mesh);
  r->set[part].closed = true;
  r->set[part].material = m;
}

int mr_set_create(mr_render *r, char *msg, size_t msg_size) {
  const mr_stage_def *s = &r->stage;
  mr_set_frame f;
  mr_set_frame_of(s, &f);
  batch b[MR_SET_PARTS];
  memset(b, 0, sizeof b);
  mr_mesh unit;
  memset(&unit, 0, sizeof unit);
  if (s->footlights && mr_shape_mesh_lod(MR_SHAPE_SPHERE, MR_SHAPE_LEVELS - 1, &unit) != 0) {
    snprintf(msg, msg_size, "out of memory for the footlights");
    return -1;
  }
  if (s->proscenium) arch(&b[MR_SET_ARCH], &b[MR_SET_TRIM], &b[MR_SET_DARK], &f);
  if (f.edge && s->floor) stage_front(&b[MR_SET_SKIRT], &f, (float)s->floor_size / 2);
  if (s->wings) wings(&b[MR_SET_DARK], s, &f);
  if (s->footlights) footlights(r, &b[MR_SET_LAMP], &b[MR_SET_DARK], &f, &unit);
  if (s->bridge) bridge(&b[MR_SET_WOOD], &f, (float)s->floor_height + 2 * MR_BACKDROP_HALF_HEIGHT);
  mr_mesh_release(&unit);
  float lamp_rgb[3], skirt[3], dark[3];
  for (int k = 0; k < 3; k++) {
    lamp_rgb[k] = s->footlight_color[k];
    skirt[k] = 0.45f * s->proscenium_color[k];
    dark[k] = s->wing_color[k];
  }
  mr_material_def lamp = material(lamp_rgb, 0.3f, 0);
  for (int k = 0; k < 3; k++)
    lamp.emissive[k] = fminf(0.9f * s->footlight_color[k] * (float)s->footlight_intensity, 4);
  upload(r, MR_SET_ARCH, &b[MR_SET_ARCH], material(s->proscenium_color, 0.85f, 0));
  upload(r, MR_SET_TRIM, &b[MR_SET_TRIM], material(s->trim_color, 0.35f, 0.8f));
  upload(r, MR_SET_DARK, &b[MR_SET_DARK], material(dark, 1.0f, 0));
  upload(r, MR_SET_SKIRT, &b[MR_SET_SKIRT], material(skirt, 0.9f, 0));
  upload(r, MR_SET_LAMP, &b[MR_SET_LAMP], lamp);
  upload(r, MR_SET_WOOD, &b[MR_SET_WOOD], material(s->floor_color, 0.8f, 0));
  bool failed = false;
  for (int k = 0; k < MR_SET_PARTS; k++) {
    failed |= b[k].failed;
    free(b[k].pos), free(b[k].nor), free(b[k].idx);
  }
  if (failed) snprintf(msg, msg_size, "out of memory for the theater's set");
  return failed ? -1 : 0;
}

bool mr_set_any(const mr_render *r) {
  for (int k = 0; k < MR_SET_PARTS; k++)
    if (r->set[k].vao) return true;
  return false;
}

void mr_set_destroy(mr_render *r) {
  for (int k = 0; k < MR_SET_PARTS; k++) mr_mesh_free(r, &r->set[k]);
}

/* The floor's square (half-side h about the origin, in x and z) cut at
 * the stage's front edge: the boards end there. */
size_t mr_set_floor_outline(const mr_stage_def *s, float h, float xz[5][2]) {
  mr_set_frame f;
  mr_set_frame_of(s, &f);
  const float sq[4][2] = { { -h, -h }, { h, -h }, { h, h }, { -h, h } };
  if (!f.edge) {
    memcpy(xz, sq, sizeof sq);
    return 4;
  }
  /* Keep where (p - edge) . front <= 0. */
  const float ex = f.origin[0] + MR_SET_APRON * f.front[0],
              ez = f.origin[2] + MR_SET_APRON * f.front[2];
  size_t m = 0;
  for (int i = 0; i < 4; i++) {
    const float *a = sq[i], *b = sq[(i + 1) % 4];
    float da = (a[0] - ex) * f.front[0] + (a[1] - ez) * f.front[2];
    float db = (b[0] - ex) * f.front[0] + (b[1] - ez) * f.front[2];
    if (da <= 0) xz[m][0] = a[0], xz[m][1] = a[1], m++;
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
      float t = da / (da - db);
      xz[m][0] = a[0] + t * (b[0] - a[0]), xz[m][1] = a[1] + t * (b[1] - a[1]), m++;
    }
  }
  return m;
}
