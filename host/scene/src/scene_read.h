/* Helpers that read typed values out of the YAML tree, each failing with
 * the node's position and what was expected there. */
#ifndef MR_SCENE_READ_H
#define MR_SCENE_READ_H

#include "mr_scene.h"
#include "scene_yaml.h"

typedef struct mr_reader {
  const char *file;
  mr_scene_error *err;
  mr_scene *scene;
} mr_reader;

#if defined(__GNUC__)
#define MR_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define MR_PRINTF(a, b)
#endif

/* Fills the error; returns -1 so callers can `return mr_scene_read_fail(...)`. */
int mr_scene_read_fail_at(mr_reader *r, int line, int column, mr_scene_status status,
               const char *fmt, ...) MR_PRINTF(5, 6);
int mr_scene_read_fail(mr_reader *r, const mr_ynode *at, mr_scene_status status,
            const char *fmt, ...) MR_PRINTF(4, 5);

/* node must be a mapping whose keys are all in allowed (NULL-terminated). */
int mr_scene_read_map(mr_reader *r, const mr_ynode *node, const char *what,
           const char *const *allowed);
int mr_scene_read_seq(mr_reader *r, const mr_ynode *node, const char *what);
int mr_scene_read_number(mr_reader *r, const mr_ynode *node, const char *what, double *out);
/* Optional key of map: *out is left alone when the key is absent. */
int mr_scene_read_number_key(mr_reader *r, const mr_ynode *map, const char *key,
                  double *out);
int mr_scene_read_positive_key(mr_reader *r, const mr_ynode *map, const char *key,
                    double *out);
int mr_scene_read_nonneg_key(mr_reader *r, const mr_ynode *map, const char *key,
                  double *out);
int mr_scene_read_vec3(mr_reader *r, const mr_ynode *node, const char *what, double out[3]);
int mr_scene_read_vec3_key(mr_reader *r, const mr_ynode *map, const char *key, double out[3]);
int mr_scene_read_bool(mr_reader *r, const mr_ynode *node, const char *what, bool *out);
int mr_scene_read_long(mr_reader *r, const mr_ynode *node, const char *what, long *out);
int mr_scene_read_name(mr_reader *r, const mr_ynode *node, const char *what,
            char out[MR_SCENE_NAME_MAX]);
/* A required key; fails naming the mapping when absent. */
const mr_ynode *mr_scene_read_need(mr_reader *r, const mr_ynode *map, const char *key,
                        const char *what);
/* Name of a particle or control point, resolved to its index. */
int mr_scene_read_particle_ref(mr_reader *r, const mr_ynode *node, size_t *out);
int mr_scene_read_control_ref(mr_reader *r, const mr_ynode *node, size_t *out);
/* Either of the two. */
int mr_scene_read_point_ref(mr_reader *r, const mr_ynode *node, mr_scene_ref *out);
/* A sequence of particle names, resolved, each at most once. */
int mr_scene_read_particle_list(mr_reader *r, const mr_ynode *node, const char *what,
                     size_t **out, size_t *count);

mr_scene_pos mr_scene_read_pos(const mr_ynode *node);

/* Sections, one file each. */
int mr_scene_read_physics(mr_reader *r, const mr_ynode *physics);
int mr_scene_read_control(mr_reader *r, const mr_ynode *control);
int mr_scene_read_expect(mr_reader *r, const mr_ynode *expect);
int mr_scene_read_groups(mr_reader *r, const mr_ynode *groups);
int mr_scene_read_parts(mr_reader *r, const mr_ynode *parts);
int mr_scene_read_forces(mr_reader *r, const mr_ynode *physics);
/* Fails unless the scene declared effect fx; `what` names the item. */
int mr_scene_read_need_effect(mr_reader *r, const mr_ynode *at, unsigned fx, const char *what);

#endif
