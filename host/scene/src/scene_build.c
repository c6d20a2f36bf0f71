/* A checked scene into a physics world: "simulate only the effects a scene
 * calls for" is the effects mask, and every item goes in as the file
 * declares it, through the physics' own add calls on the definitions the
 * reader filled. */
#include "mr_scene_world.h"
#include "scene_read.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static mr_scene_status fail(const mr_scene *s, mr_scene_error *err, mr_scene_pos at,
                            mr_scene_status st, const char *fmt, ...) MR_PRINTF(5, 6);

static mr_scene_status fail(const mr_scene *s, mr_scene_error *err, mr_scene_pos at,
                            mr_scene_status st, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  err->status = st;
  err->line = at.line;
  err->column = at.column;
  vsnprintf(err->message, sizeof err->message, fmt, ap);
  va_end(ap);
  if (at.line > 0)
    snprintf(err->text, sizeof err->text, "%s:%d:%d: %s", s->path, at.line, at.column,
             err->message);
  else
    snprintf(err->text, sizeof err->text, "%s: %s", s->path, err->message);
  return st;
}

/* An add call's verdict: on a refusal, the item's place in the file. */
static mr_scene_status added(const mr_scene *s, const mr_scene_world *sw, mr_scene_error *err,
                             mr_scene_pos at, const char *what, mr_status st) {
  if (st == MR_OK) return MR_SCENE_OK;
  return fail(s, err, at, st == MR_ERR_NOMEM ? MR_SCENE_ERR_NOMEM : MR_SCENE_ERR_BUILD,
              "the physics refused %s (%s): %s", what, mr_status_name(st),
              mr_world_last_error(sw->world));
}

/* The reader wrote world ids for particles and control points; the
 * physics numbers particles in creation order, which is the file's. */
static mr_scene_status numbered(const mr_scene *s, mr_scene_error *err, mr_scene_pos at, int id,
                                size_t want) {
  if (id == (int)want) return MR_SCENE_OK;
  return fail(s, err, at, MR_SCENE_ERR_BUILD, "the physics numbered particle %zu as %d", want, id);
}

static mr_scene_status add_particles(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  mr_scene_status rc = MR_SCENE_OK;
  for (size_t i = 0; i < s->n_particles && rc == MR_SCENE_OK; i++) {
    const mr_scene_particle *p = &s->particles[i];
    rc = added(s, sw, err, p->pos, "the particle",
               mr_world_add_particle(sw->world, &p->def, &sw->particle_ids[i]));
    if (rc == MR_SCENE_OK) rc = numbered(s, err, p->pos, sw->particle_ids[i], i);
    if (rc == MR_SCENE_OK && p->pinned) {
      mr_pin_def pin = mr_default_pin_def();
      pin.particle = sw->particle_ids[i];
      int id;
      rc = added(s, sw, err, p->pos, "the pin", mr_world_add_pin(sw->world, &pin, &id));
    }
  }
  return rc;
}

/* Each frame at its pose at t = 0, and its points as kinematic particles. */
static mr_scene_status add_control(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  mr_scene_status rc = MR_SCENE_OK;
  for (size_t k = 0; k < s->n_frames && rc == MR_SCENE_OK; k++) {
    const mr_scene_frame *f = &s->frames[k];
    mr_frame_def fd = mr_default_frame_def();
    mr_scene_frame_pose_at(s, k, 0.0, &fd.pose);
    rc = added(s, sw, err, f->pos, "the control frame",
               mr_world_add_frame(sw->world, &fd, &sw->frames[k]));
    for (size_t i = f->first_point; i < f->first_point + f->n_points && rc == MR_SCENE_OK; i++) {
      const mr_scene_control_point *c = &s->control_points[i];
      mr_particle_def d = mr_default_particle_def();
      d.frame = sw->frames[k];
      mr_scene_control_point_world(s, i, &fd.pose, d.position);
      rc = added(s, sw, err, c->pos, "the control point",
                 mr_world_add_particle(sw->world, &d, &sw->control_ids[i]));
      if (rc == MR_SCENE_OK) rc = numbered(s, err, c->pos, sw->control_ids[i], s->n_particles + i);
    }
  }
  return rc;
}

static mr_scene_status add_constraints(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  int id;
  mr_scene_status rc = MR_SCENE_OK;
  for (size_t i = 0; i < s->n_distances && rc == MR_SCENE_OK; i++)
    rc = added(s, sw, err, s->distances[i].pos, "the constraint",
               mr_world_add_distance(sw->world, &s->distances[i].def, &id));
  for (size_t i = 0; i < s->n_groups && rc == MR_SCENE_OK; i++)
    rc = added(s, sw, err, s->groups[i].pos, "the rigid group",
               mr_world_add_rigid_group(sw->world, &s->groups[i].def, &id));
  return rc;
}

static mr_scene_status add_forces(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  int id;
  mr_scene_status rc = MR_SCENE_OK;
  for (size_t i = 0; i < s->n_forces && rc == MR_SCENE_OK; i++) {
    const char *what;
    mr_status st = mr_scene_force_add(sw->world, &s->forces[i], &id, &what);
    rc = added(s, sw, err, s->forces[i].pos, what, st);
  }
  return rc;
}

static mr_scene_status add_collisions(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  int id;
  mr_scene_status rc = MR_SCENE_OK;
  if (s->floor.present)
    rc = added(s, sw, err, s->floor.pos, "the floor",
               mr_world_add_plane(sw->world, &s->floor.def, &id));
  for (size_t i = 0; i < s->n_parts && rc == MR_SCENE_OK; i++)
    rc = added(s, sw, err, s->parts[i].pos, "the collision part",
               mr_world_add_part(sw->world, &s->parts[i].def, &id));
  return rc;
}

static mr_scene_status create_world(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  mr_scene_pos top = { 0, 0 };
  sw->particle_ids = calloc(s->n_particles ? s->n_particles : 1, sizeof *sw->particle_ids);
  sw->control_ids = calloc(s->n_control_points ? s->n_control_points : 1, sizeof *sw->control_ids);
  sw->frames = malloc((s->n_frames ? s->n_frames : 1) * sizeof *sw->frames);
  if (sw->particle_ids == NULL || sw->control_ids == NULL || sw->frames == NULL)
    return fail(s, err, top, MR_SCENE_ERR_NOMEM, "out of memory");
  sw->n_particles = s->n_particles;
  sw->n_control = s->n_control_points;
  sw->n_frames = s->n_frames;
  for (size_t k = 0; k < s->n_frames; k++) sw->frames[k] = -1;
  char msg[256] = "";
  if (mr_world_create(&s->world, &sw->world, msg, sizeof msg) != MR_OK)
    return fail(s, err, top, MR_SCENE_ERR_BUILD, "the physics refused the world settings: %s", msg);
  return MR_SCENE_OK;
}

typedef mr_scene_status (*build_stage)(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err);

mr_scene_status mr_scene_build(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  /* Particles before the control points, which are numbered after them;
   * both before anything that names them. */
  static const build_stage stages[] = { create_world,    add_particles, add_control,
                                        add_constraints, add_forces,    add_collisions };
  memset(sw, 0, sizeof *sw);
  memset(err, 0, sizeof *err);
  mr_scene_status rc = MR_SCENE_OK;
  for (size_t i = 0; i < sizeof stages / sizeof stages[0] && rc == MR_SCENE_OK; i++)
    rc = stages[i](s, sw, err);
  if (rc != MR_SCENE_OK) mr_scene_world_free(sw);
  return rc;
}

double *mr_scene_start_positions(const mr_scene *s, size_t *n, mr_scene_error *err) {
  mr_scene_world sw;
  *n = 0;
  if (mr_scene_build(s, &sw, err) != MR_SCENE_OK) return NULL;
  int count = mr_world_particle_count(sw.world);
  double *xyz = calloc((size_t)(count > 0 ? count : 1) * 3, sizeof *xyz);
  if (xyz != NULL) {
    mr_world_positions(sw.world, xyz, count);
    *n = (size_t)count;
  } else {
    err->status = MR_SCENE_ERR_NOMEM;
    snprintf(err->message, sizeof err->message, "out of memory");
    snprintf(err->text, sizeof err->text, "%s: out of memory", s->path ? s->path : "scene");
  }
  mr_scene_world_free(&sw);
  return xyz;
}

void mr_scene_world_free(mr_scene_world *sw) {
  if (sw->world != NULL) mr_world_destroy(sw->world);
  free(sw->particle_ids);
  free(sw->control_ids);
  free(sw->frames);
  memset(sw, 0, sizeof *sw);
}
