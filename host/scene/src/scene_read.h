/* Helpers that read typed values out of the YAML tree, each failing with
 * the node's position and what was expected there. Private to mr_scene,
 * yet prefixed: a static library exports every non-static name. */
#ifndef MR_SCENE_READ_H
#define MR_SCENE_READ_H

#include "mr_scene.h"
#include "scene_yaml.h"

/* Two particles closer than this are one point: every constraint or force
 * between them has no direction (a zero row of J, §5.2). */
#define MR_SCENE_COINCIDENT_M 1e-6

typedef struct mr_reader {
  const char *file;
  mr_scene_error *err;
  mr_scene *scene;
  /* While a puppet is read: its name, which qualifies the names it
   * declares ("alice.hand"), its world puppet number and its placement. */
  const char *puppet;
  int puppet_id;
  double offset[3];
  /* The particles read so far by name and by place, for lookups and
   * checks in O(1) each (scene_index.c). */
  struct mr_scene_index *index;
  /* Room in scene->stage.models, which grows by more than one at a time. */
  size_t models_cap;
  /* 1: the set is not sized nor the audience framed (mr_scene_load_unframed). */
  int unframed;
} mr_reader;

#if defined(__GNUC__)
#define MR_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define MR_PRINTF(a, b)
#endif

/* Fills the error; returns -1 so callers can `return mr_scene_read_fail(...)`. */
int mr_scene_read_fail_at(mr_reader *r, int line, int column, mr_scene_status status,
                          const char *fmt, ...) MR_PRINTF(5, 6);
int mr_scene_read_fail(mr_reader *r, const mr_ynode *at, mr_scene_status status, const char *fmt,
                       ...) MR_PRINTF(4, 5);
mr_scene_pos mr_scene_read_pos(const mr_ynode *node);

/* node must be a mapping whose keys are all in allowed (NULL-terminated). */
int mr_scene_read_map(mr_reader *r, const mr_ynode *node, const char *what,
                      const char *const *allowed);
int mr_scene_read_seq(mr_reader *r, const mr_ynode *node, const char *what);
/* A finite decimal number within its documented range (scene_ranges.c). */
int mr_scene_read_number(mr_reader *r, const mr_ynode *node, const char *what, double *out);
/* The same before its range: the caller checks what it can name better,
 * then calls mr_scene_range_check. */
int mr_scene_read_quantity(mr_reader *r, const mr_ynode *node, const char *what, double *out);
int mr_scene_read_vec3(mr_reader *r, const mr_ynode *node, const char *what, double out[3]);
int mr_scene_read_bool(mr_reader *r, const mr_ynode *node, const char *what, bool *out);
int mr_scene_read_long(mr_reader *r, const mr_ynode *node, const char *what, long *out);
int mr_scene_read_name(mr_reader *r, const mr_ynode *node, const char *what,
                       char out[MR_SCENE_NAME_MAX]);
/* An item that is a mapping of `keys` with a required name: the name's
 * node, or NULL after an error. `label` names the name ("group name"). */
const mr_ynode *mr_scene_read_named(mr_reader *r, const mr_ynode *item, const char *what,
                                    const char *const *keys, const char *label,
                                    char name[MR_SCENE_NAME_MAX]);
/* A required key; fails naming the mapping when absent. */
const mr_ynode *mr_scene_read_need(mr_reader *r, const mr_ynode *map, const char *key,
                                   const char *what);

/* Optional keys of a mapping, read into a definition struct at the given
 * offsets; a key the file leaves out keeps what the default maker put
 * there. One table per struct replaces a reader per field. */
typedef enum mr_scene_field_kind {
  MR_SCENE_FIELD_NUMBER,   /* any finite double */
  MR_SCENE_FIELD_POSITIVE, /* double > 0 */
  MR_SCENE_FIELD_NONNEG,   /* double >= 0 */
  MR_SCENE_FIELD_UNIT,     /* double in [0, 1] (restitution) */
  MR_SCENE_FIELD_INT,      /* int in [lo, hi] */
  MR_SCENE_FIELD_VEC3      /* double[3] */
} mr_scene_field_kind;

typedef struct mr_scene_field {
  const char *key;
  mr_scene_field_kind kind;
  size_t offset;
  long lo, hi; /* MR_SCENE_FIELD_INT */
} mr_scene_field;

int mr_scene_read_fields(mr_reader *r, const mr_ynode *map, const mr_scene_field *fields, size_t n,
                         void *def);
/* The same for one field. */
int mr_scene_read_field(mr_reader *r, const mr_ynode *map, const mr_scene_field *field, void *def);

/* A word from an enum's own name table: parse() it with the defining
 * library's parser; on failure list name(i) for every i the table has. */
typedef int (*mr_scene_parse_fn)(const char *word, int *out);
typedef const char *(*mr_scene_name_fn)(int i);
int mr_scene_read_choice(mr_reader *r, const mr_ynode *map, const char *key,
                         mr_scene_parse_fn parse, mr_scene_name_fn name, int *out);
/* "a, b, c": name(i) from i = 0 until the table answers "unknown". */
void mr_scene_list_names(char *out, size_t size, mr_scene_name_fn name);

/* A sequence of items, each a mapping read by `read` into its slot of a
 * fresh array of `size`-byte items (zeroed). The items need `effect` among
 * the scene's effects when there are any; `declared` completes "... declared
 * but effect ... is not listed" ("springs are"). *count grows before each
 * item is read, so a half-read item is still freed. */
typedef int (*mr_scene_item_fn)(mr_reader *r, const mr_ynode *item, void *slot);
int mr_scene_read_items(mr_reader *r, const mr_ynode *seq, const char *what, uint32_t effect,
                        const char *declared, size_t size, void **items, size_t *count,
                        mr_scene_item_fn read);

/* Names of particles and control points, as world ids. */
int mr_scene_read_particle(mr_reader *r, const mr_ynode *node, int *id);
int mr_scene_read_control_point(mr_reader *r, const mr_ynode *node, int *id);
int mr_scene_read_point(mr_reader *r, const mr_ynode *node, int *id); /* either */

/* The model file NAME of the scene at scene_path, along the search path:
 * the scene's folder, MARIONETTE_PATH's folders, the installed scenes'
 * folder. path gets the first place that has it, else the scene's own
 * (and looked every other place tried, ", "-separated). -1 when the
 * scene's own place does not fit in size. */
int mr_scene_model_find(const char *scene_path, const char *name, char *path, size_t size,
                        char *looked, size_t looked_size);
bool mr_scene_is_control_id(const mr_scene *scene, int id);
const char *mr_scene_point_name(const mr_scene *scene, int id);
/* A sequence of particle names, each at most once, as world ids. */
int mr_scene_read_particle_list(mr_reader *r, const mr_ynode *node, const char *what, int **out,
                                int *count);
/* [a, b] under `between`: two distinct points, not both control points. */
int mr_scene_read_between(mr_reader *r, const mr_ynode *item, const char *what, int *a, int *b);

/* The documented range of a quantity, by its key (scene_ranges.c). */
typedef struct mr_scene_range {
  const char *key;
  double lo, hi;
  const char *unit;
} mr_scene_range;
const mr_scene_range *mr_scene_range_of(const char *key); /* never NULL */
const mr_scene_range *mr_scene_range_at(int i);           /* NULL past the end */
/* 0 when lo <= v <= hi for key, else fails at node naming the range. */
int mr_scene_range_check(mr_reader *r, const mr_ynode *node, const char *key, double v);

/* Indexes the particles read since the last call by name and checks that
 * no two share a name or a place; the error names the later one of a
 * pair. */
typedef struct mr_scene_index mr_scene_index;
int mr_scene_index_particles(mr_reader *r);
void mr_scene_index_free(mr_reader *r);
/* A particle's index by its full name, or (size_t)-1. */
size_t mr_scene_lookup_particle(const mr_reader *r, const char *name);
/* name qualified by the puppet being read ("alice.hand"); -1 when it does
 * not fit. */
int mr_scene_qualify(const mr_reader *r, const char *name, char out[MR_SCENE_NAME_MAX]);

/* Fails unless the scene declared one of the effect bits; `what` names the
 * item ("springs are"). */
int mr_scene_read_need_effect(mr_reader *r, const mr_ynode *at, uint32_t effect, const char *what);
/* The name a scene file uses for one effect bit. */
const char *mr_scene_effect_name(uint32_t effect_bit);

/* A section read by fn when the file has it (key under n). */
int mr_scene_read_optional(mr_reader *r, const mr_ynode *n, const char *key,
                           int (*fn)(mr_reader *, const mr_ynode *));

/* Sections, one file each. */
int mr_scene_read_physics(mr_reader *r, const mr_ynode *physics);
/* A control frame: the scene's, or the puppet being read's. */
int mr_scene_read_control(mr_reader *r, const mr_ynode *control);
void mr_scene_frame_defaults(mr_scene_frame *f);
int mr_scene_read_expect(mr_reader *r, const mr_ynode *expect);
int mr_scene_read_mappings(mr_reader *r, const mr_ynode *mapping);
int mr_scene_read_groups(mr_reader *r, const mr_ynode *groups);
int mr_scene_read_parts(mr_reader *r, const mr_ynode *parts);
int mr_scene_read_particles(mr_reader *r, const mr_ynode *particles);
int mr_scene_read_constraints(mr_reader *r, const mr_ynode *constraints);
/* physics.puppets in two passes: every puppet's particles first, so that
 * world ids stay fixed before anything names a control point; then their
 * constraints, groups, forces and parts. */
int mr_scene_read_puppet_particles(mr_reader *r, const mr_ynode *puppets);
int mr_scene_read_puppet_items(mr_reader *r, const mr_ynode *puppets);
/* Each puppet's own control frame, after the scene's, before any force
 * names a control point. */
int mr_scene_read_puppet_controls(mr_reader *r, const mr_ynode *puppets);
int mr_scene_read_forces(mr_reader *r, const mr_ynode *physics);
/* Adds one force to a world with its kind's add call; *what names the item
 * for a refusal ("the spring"). */
mr_status mr_scene_force_add(mr_world *w, const mr_scene_force *f, int *id, const char **what);
/* The keys under physics: that the force table reads, in table order. */
size_t mr_scene_force_keys(const char **out, size_t max);

/* The stage (models:, lights:, stage:, camera:) into scene->stage, after
 * physics, so every name is known (scene_stage.c). */
int mr_scene_read_stage(mr_reader *r, const mr_ynode *root);
/* stage.curtain and stage.follow_spot (scene_curtain.c), from the stage
 * section's node. */
int mr_scene_read_curtain(mr_reader *r, const mr_ynode *stage);
void mr_scene_stage_free(mr_scene *scene);
/* models: into scene->stage.models (scene_models.c). */
int mr_scene_read_models(mr_reader *r, const mr_ynode *models);
/* [r, g, b], each 0..1 as the range of `key` says. */
int mr_scene_read_rgb(mr_reader *r, const mr_ynode *node, const char *key, float out[3]);
/* Appends a model to scene->stage.models; NULL when out of memory. */
mr_model_def *mr_scene_stage_add_model(mr_reader *r, const mr_ynode *at);
/* Room for `more` models beyond those held, in one step, for a batch of
 * known size; fails at `at` when out of memory. */
int mr_scene_stage_reserve_models(mr_reader *r, const mr_ynode *at, size_t more);
/* What the physics implies for the stage: strings and control frames as
 * lines, collision spheres, models when the file has none, the floor's
 * height, a camera that frames the puppets (scene_rigging.c). */
int mr_scene_stage_rigging(mr_reader *r, const mr_ynode *root);
/* Every point of the show (particles, then control points) at evenly
 * spaced moments over sim.duration, as scene_audience.c estimates them
 * without the physics: 3 *count doubles with room for `extra` points
 * after them, or NULL when memory runs out. */
double *mr_scene_show_points(const mr_scene *s, size_t extra, size_t *count);
/* The audience's camera (scene_audience.c) into the stage's orbit, for a
 * scene without camera.orbit, from the show's points (as
 * mr_scene_show_points gives them, with room for MR_SET_FRAMED more),
 * which it overwrites; nothing without points. */
void mr_scene_frame_audience(mr_scene *s, double *show);
/* The theater's set sized from the show's count points where the scene
 * left its size at 0 (scene_set.c). */
void mr_scene_size_set(mr_scene *s, const double *show, size_t count);
/* The points of the set the audience's camera frames (the proscenium's
 * opening, a band of the arch about it and the footlights' middle), at
 * most MR_SET_FRAMED, into xyz; returns how many. */
enum { MR_SET_FRAMED = 3 };
size_t mr_scene_set_framed(const mr_stage_def *st, double *xyz);

#endif
