/* A checked scene into a physics world: "simulate only the effects a scene
 * calls for" is the effects mask, and every item goes in as the file
 * declares it. */
#include "mr_scene_world.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


uint32_t mr_scene_physics_effects(unsigned fx) {
  static const uint32_t map[MR_SCENE_FX_COUNT] = {
      MR_EFFECT_GRAVITY,      MR_EFFECT_DRAG,         MR_EFFECT_SPRINGS,
      MR_EFFECT_STRINGS,      MR_EFFECT_ANTIGRAVITY,  MR_EFFECT_TRIGGERED,
      MR_EFFECT_SINE_SPRINGS, MR_EFFECT_CONSTRAINTS,  MR_EFFECT_PLANES,
      MR_EFFECT_SELF_COLLISION, MR_EFFECT_STRING_CORRECTION, MR_EFFECT_FRAMES};
  uint32_t out = 0;
  for (unsigned i = 0; i < MR_SCENE_FX_COUNT; i++)
    if (fx & (1u << i))
      out |= map[i];
  return out;
}

mr_pose mr_scene_pose_to_physics(const mr_scene_pose *p) {
  return mr_pose_from_euler_deg(p->position, p->rotation_deg);
}

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

/* The physics refused an item: name the item's place in the file. */
static mr_scene_status refused(const mr_scene *s, const mr_scene_world *sw, mr_scene_error *err,
                               mr_scene_pos at, const char *what, mr_status st) {
  return fail(s, err, at, st == MR_ERR_NOMEM ? MR_SCENE_ERR_NOMEM : MR_SCENE_ERR_BUILD,
              "the physics refused %s (%s): %s", what, mr_status_name(st),
              mr_world_last_error(sw->world));
}

static void set_if(double *dst, double v) {
  if (!isnan(v))
    *dst = v;
}

static int ref_id(const mr_scene_world *sw, mr_scene_ref r) {
  return r.control ? sw->control_ids[r.index] : sw->particle_ids[r.index];
}

static mr_world_def world_def(const mr_scene *s) {
  const mr_scene_settings *st = &s->settings;
  mr_world_def d = mr_default_world_def();
  memcpy(d.gravity, s->gravity, sizeof d.gravity);
  d.effects = mr_scene_physics_effects(s->effects);
  if (st->integrator[0] != '\0')
    mr_integrator_parse(st->integrator, &d.integrator);
  if (st->method[0] != '\0')
    mr_solve_method_parse(st->method, &d.solver);
  set_if(&d.dt_initial, st->dt_initial);
  set_if(&d.dt_min, st->dt_min);
  set_if(&d.dt_max, st->dt_max);
  set_if(&d.deviation_low, st->threshold_min);
  set_if(&d.deviation_high, st->threshold_max);
  set_if(&d.divergence_bound, st->divergence);
  set_if(&d.deviation_length, st->deviation_length);
  if (st->max_steps > 0)
    d.max_steps_per_call = (int)st->max_steps;
  set_if(&d.solver_tolerance, st->tolerance);
  if (st->max_iterations > 0)
    d.solver_max_iterations = (int)st->max_iterations;
  set_if(&d.ks, st->ks);
  set_if(&d.kd, st->kd);
  d.drag = s->drag;
  set_if(&d.contact_slop, st->contact_slop);
  set_if(&d.rest_speed, st->rest_speed);
  set_if(&d.string_max_stretch, st->string_max_stretch);
  if (st->string_iterations > 0)
    d.string_correction_iterations = (int)st->string_iterations;
  return d;
}

static mr_scene_status add_particles(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  for (size_t i = 0; i < s->n_particles; i++) {
    const mr_scene_particle *p = &s->particles[i];
    mr_particle_def d = mr_default_particle_def();
    d.mass = p->mass;
    memcpy(d.position, p->position, sizeof d.position);
    memcpy(d.velocity, p->velocity, sizeof d.velocity);
    d.radius = p->radius;
    mr_status st = mr_world_add_particle(sw->world, &d, &sw->particle_ids[i]);
    if (st != MR_OK)
      return refused(s, sw, err, p->pos, "the particle", st);
    if (p->pinned) {
      mr_pin_def pin = mr_default_pin_def();
      pin.particle = sw->particle_ids[i];
      int id;
      if ((st = mr_world_add_pin(sw->world, &pin, &id)) != MR_OK)
        return refused(s, sw, err, p->pos, "the pin", st);
    }
  }
  if (s->n_control_points == 0)
    return MR_SCENE_OK;
  mr_scene_pose pose0;
  mr_scene_control_pose_at(s, 0.0, &pose0);
  mr_frame_def fd = mr_default_frame_def();
  fd.pose = mr_scene_pose_to_physics(&pose0);
  mr_status st = mr_world_add_frame(sw->world, &fd, &sw->frame);
  if (st != MR_OK)
    return refused(s, sw, err, s->control_points[0].pos, "the control frame", st);
  for (size_t i = 0; i < s->n_control_points; i++) {
    mr_particle_def d = mr_default_particle_def();
    d.frame = sw->frame;
    mr_scene_control_point_world(s, i, &pose0, d.position);
    if ((st = mr_world_add_particle(sw->world, &d, &sw->control_ids[i])) != MR_OK)
      return refused(s, sw, err, s->control_points[i].pos, "the control point", st);
  }
  return MR_SCENE_OK;
}

static mr_scene_status add_constraints(const mr_scene *s, mr_scene_world *sw,
                                       mr_scene_error *err) {
  int id;
  mr_status st;
  for (size_t i = 0; i < s->n_distances; i++) {
    const mr_scene_distance *c = &s->distances[i];
    mr_distance_def d = mr_default_distance_def();
    d.a = sw->particle_ids[c->a];
    d.b = sw->particle_ids[c->b];
    d.length = c->length;
    if ((st = mr_world_add_distance(sw->world, &d, &id)) != MR_OK)
      return refused(s, sw, err, c->pos, "the constraint", st);
  }
  for (size_t i = 0; i < s->n_groups; i++) {
    const mr_scene_group *g = &s->groups[i];
    int *ids = malloc(g->count * sizeof *ids);
    if (ids == NULL)
      return fail(s, err, g->pos, MR_SCENE_ERR_NOMEM, "out of memory");
    for (size_t k = 0; k < g->count; k++)
      ids[k] = sw->particle_ids[g->members[k]];
    mr_rigid_group_def d = mr_default_rigid_group_def();
    d.particles = ids;
    d.count = (int)g->count;
    st = mr_world_add_rigid_group(sw->world, &d, &id);
    free(ids);
    if (st != MR_OK)
      return refused(s, sw, err, g->pos, "the rigid group", st);
  }
  return MR_SCENE_OK;
}

static mr_scene_status add_forces(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  int id;
  mr_status st;
  for (size_t i = 0; i < s->n_springs; i++) {
    const mr_scene_spring *x = &s->springs[i];
    mr_spring_def d = mr_default_spring_def();
    d.a = sw->particle_ids[x->a];
    d.b = sw->particle_ids[x->b];
    set_if(&d.rest_length, x->rest);
    set_if(&d.stiffness, x->stiffness);
    set_if(&d.damping, x->damping);
    if ((st = mr_world_add_spring(sw->world, &d, &id)) != MR_OK)
      return refused(s, sw, err, x->pos, "the spring", st);
  }
  for (size_t i = 0; i < s->n_strings; i++) {
    const mr_scene_string *x = &s->strings[i];
    mr_string_def d = mr_default_string_def();
    d.frame_particle = sw->control_ids[x->control];
    d.puppet_particle = sw->particle_ids[x->particle];
    set_if(&d.rest_length, x->rest);
    set_if(&d.stiffness, x->stiffness);
    set_if(&d.damping, x->damping);
    if ((st = mr_world_add_string(sw->world, &d, &id)) != MR_OK)
      return refused(s, sw, err, x->pos, "the string", st);
  }
  for (size_t i = 0; i < s->n_sine_springs; i++) {
    const mr_scene_sine_spring *x = &s->sine_springs[i];
    mr_sine_spring_def d = mr_default_sine_spring_def();
    d.a = ref_id(sw, x->a);
    d.b = ref_id(sw, x->b);
    set_if(&d.rest_length, x->rest);
    set_if(&d.max_force, x->max_force);
    set_if(&d.reach, x->reach);
    set_if(&d.damping, x->damping);
    if ((st = mr_world_add_sine_spring(sw->world, &d, &id)) != MR_OK)
      return refused(s, sw, err, x->pos, "the sine spring", st);
  }
  for (size_t i = 0; i < s->n_antigravities; i++) {
    const mr_scene_antigravity *x = &s->antigravities[i];
    mr_antigravity_def d = mr_default_antigravity_def();
    d.acted = ref_id(sw, x->acted);
    d.trigger = ref_id(sw, x->trigger);
    set_if(&d.fraction, x->fraction);
    set_if(&d.max_scale, x->max_scale);
    if ((st = mr_world_add_antigravity(sw->world, &d, &id)) != MR_OK)
      return refused(s, sw, err, x->pos, "the antigravity force", st);
  }
  for (size_t i = 0; i < s->n_triggered; i++) {
    const mr_scene_triggered *x = &s->triggered[i];
    mr_triggered_def d = mr_default_triggered_def();
    d.acted = ref_id(sw, x->acted);
    d.control = ref_id(sw, x->control);
    d.trigger = ref_id(sw, x->trigger);
    set_if(&d.gain, x->gain);
    set_if(&d.max_force, x->max_force);
    if ((st = mr_world_add_triggered(sw->world, &d, &id)) != MR_OK)
      return refused(s, sw, err, x->pos, "the triggered force", st);
  }
  return MR_SCENE_OK;
}

static mr_scene_status add_collisions(const mr_scene *s, mr_scene_world *sw,
                                      mr_scene_error *err) {
  int id;
  mr_status st;
  if (s->floor.present) {
    mr_plane_def d = mr_default_plane_def();
    d.normal[0] = 0;
    d.normal[1] = 1;
    d.normal[2] = 0;
    d.offset = s->floor.height;
    d.restitution = s->floor.restitution;
    d.friction = s->floor.friction;
    if ((st = mr_world_add_plane(sw->world, &d, &id)) != MR_OK)
      return refused(s, sw, err, s->floor.pos, "the floor", st);
  }
  for (size_t i = 0; i < s->n_parts; i++) {
    const mr_scene_part *p = &s->parts[i];
    int *ids = malloc(p->count * sizeof *ids);
    if (ids == NULL)
      return fail(s, err, p->pos, MR_SCENE_ERR_NOMEM, "out of memory");
    for (size_t k = 0; k < p->count; k++)
      ids[k] = sw->particle_ids[p->members[k]];
    mr_part_def d = mr_default_part_def();
    d.particles = ids;
    d.count = (int)p->count;
    set_if(&d.radius, p->radius);
    set_if(&d.restitution, p->restitution);
    set_if(&d.friction, p->friction);
    if (p->segment_spheres >= 0)
      d.segment_spheres = p->segment_spheres;
    st = mr_world_add_part(sw->world, &d, &id);
    free(ids);
    if (st != MR_OK)
      return refused(s, sw, err, p->pos, "the collision part", st);
  }
  return MR_SCENE_OK;
}

mr_scene_status mr_scene_build(const mr_scene *s, mr_scene_world *sw, mr_scene_error *err) {
  memset(sw, 0, sizeof *sw);
  memset(err, 0, sizeof *err);
  sw->frame = -1;
  mr_scene_pos top = {0, 0};
  sw->particle_ids = calloc(s->n_particles ? s->n_particles : 1, sizeof *sw->particle_ids);
  sw->control_ids = calloc(s->n_control_points ? s->n_control_points : 1, sizeof *sw->control_ids);
  if (sw->particle_ids == NULL || sw->control_ids == NULL) {
    mr_scene_world_free(sw);
    return fail(s, err, top, MR_SCENE_ERR_NOMEM, "out of memory");
  }
  sw->n_particles = s->n_particles;
  sw->n_control = s->n_control_points;
  mr_world_def def = world_def(s);
  char msg[256] = "";
  mr_status st = mr_world_create(&def, &sw->world, msg, sizeof msg);
  if (st != MR_OK) {
    mr_scene_world_free(sw);
    return fail(s, err, top, MR_SCENE_ERR_BUILD, "the physics refused the world settings: %s",
                msg);
  }
  mr_scene_status rc = add_particles(s, sw, err);
  if (rc == MR_SCENE_OK)
    rc = add_constraints(s, sw, err);
  if (rc == MR_SCENE_OK)
    rc = add_forces(s, sw, err);
  if (rc == MR_SCENE_OK)
    rc = add_collisions(s, sw, err);
  if (rc != MR_SCENE_OK)
    mr_scene_world_free(sw);
  return rc;
}

void mr_scene_world_free(mr_scene_world *sw) {
  if (sw->world != NULL)
    mr_world_destroy(sw->world);
  free(sw->particle_ids);
  free(sw->control_ids);
  memset(sw, 0, sizeof *sw);
  sw->frame = -1;
}
