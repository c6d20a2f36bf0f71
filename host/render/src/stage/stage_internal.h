/* The stage's insides, shared by its files. Private to mr_stage. */
#ifndef MR_STAGE_INTERNAL_H
#define MR_STAGE_INTERNAL_H

#include "mr_stage.h"

/* A freeform bone turns with the bones nearest it at rest, at most this
 * many (mr_stage_bones_prepare). */
enum { MR_STAGE_BONE_NEIGHBOURS = 4 };

/* How a freeform bone finds its turn, chosen once from its neighbours at
 * rest. */
typedef enum mr_stage_bone_fit {
  MR_STAGE_FIT_NONE = 0, /* no neighbour: the bone only moves */
  MR_STAGE_FIT_AXIS,     /* neighbours on one line: the shortest turn of that line */
  MR_STAGE_FIT_FULL      /* neighbours spanning a plane: Horn's best rotation */
} mr_stage_bone_fit;

typedef struct mr_stage_model {
  int slot;           /* index into items (PARTICLE, LINK, RIGID) or skins */
  mr_pose rest_frame; /* RIGID: the three particles' frame at the start */
  size_t first_bone;  /* FREEFORM: into the stage's bone arrays */
  int *bones;         /* FREEFORM: the copy the def points to */
  double *bones_rest; /* FREEFORM: the copy the def points to */
} mr_stage_model;

struct mr_stage {
  mr_stage_def def; /* its arrays point to the copies below */
  mr_model_def *models;
  mr_stage_model *state;
  mr_star *stars;
  int *strings;
  int *frame_points, *frame_point_count;
  size_t n;            /* points */
  double *shown;       /* 3 n: every point's last finite position (lines) */
  mr_draw_item *items; /* the collision spheres' last (mr_stage_show_spheres) */
  size_t n_items, n_sphere_items;
  mr_draw_skin *skins;
  size_t n_skins;
  mr_pose *bone_poses; /* every freeform model's, model by model */
  int *neighbours;     /* MR_STAGE_BONE_NEIGHBOURS per bone, local indices, -1 unused */
  unsigned char *fit;  /* mr_stage_bone_fit per bone */
  size_t n_bones;
  mr_draw_line *lines;
  size_t n_lines;
  mr_draw_list list;
  /* The follow spot's points (stage_curtain.c): the puppets' model
   * points, not the bars'; and a scratch of 3 n_spot doubles. */
  int *spot_points;
  double *spot_xyz;
  size_t n_spot;
};

/* The follow spot's points, chosen once (stage_curtain.c): 0, or -1 out
 * of memory. */
int mr_stage_spot_prepare(mr_stage *s);
/* The follow spot aimed at its points where they were last finite. */
void mr_stage_spot_update(mr_stage *s);

/* Chooses each bone of freeform model m its neighbours and its fit. */
void mr_stage_bones_prepare(mr_stage *s, size_t m);
/* Poses the bones of freeform model m from the points at xyz: 0, or -1
 * (poses untouched) when one of its points is not finite. */
int mr_stage_bones_update(mr_stage *s, size_t m, const double *xyz);

#endif
