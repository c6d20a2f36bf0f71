/* The show's own state, shared by the files that make up mr_show (show.c,
 * show_tell.c). Private to mr_theater. */
#ifndef MR_SHOW_INTERNAL_H
#define MR_SHOW_INTERNAL_H

#include "mr_control.h"
#include "mr_io.h"
#include "mr_show.h"
#include "theater_internal.h"

/* One glove, its take, and what the user was last told of it. */
typedef struct show_glove {
  mr_glove *glove;
  mr_rec_writer take;
  bool recording, take_open;
  char take_error[320];
  mr_glove_state told_state, seen_state;
  double seen_since; /* show time seen_state began */
  bool told_silent;
  bool told_two;    /* a second publisher on the glove's topic, told */
  gp_counters told; /* the decoder's counters when corrupt frames were last told */
  double told_at;   /* show time of that */
  /* Layered playback: the take beneath and the channels armed over it;
   * the glove's clock at its last poll (show time unless it is read on
   * the glove clock); the show time its bytes are recorded at. */
  bool paced;
  double now;
  const double *show_t;
} show_glove;

/* One control frame: its glove, its mapping and where it heads. */
typedef struct show_frame {
  int glove; /* index into gloves, -1 until bound */
  mr_control *control;
  mr_pose target;
  mr_glove_follow follow; /* how fast the target moves */
  uint64_t samples_seen;
  mr_channel_state states[MR_CONTROL_CHANNELS]; /* as last told to the user */
} show_frame;

struct mr_show {
  const mr_scene *scene;
  mr_scene_world sw;
  show_glove gloves[MR_SHOW_MAX_GLOVES];
  const char *sources[MR_SHOW_MAX_GLOVES];
  size_t n_gloves;
  show_frame *frames;
  size_t n_frames;
  mr_scheduler *sch;
  mr_clock clock;
  mr_show_hooks hooks;
  double duration;
  bool interpolate;
  double sum_lead, lead_max;
  uint64_t frames_stepped;
  mr_interp ip;                          /* the frame's positions, interpolated or the world's */
  double *start_xyz;                     /* every particle where it started, for a reset */
  unsigned resets_asked, mappings_asked; /* done as the next frame starts */
  mr_show_frame scratch;                 /* the snapshot the hooks are handed */
  bool ended;
  mr_scheduler_stats end_stats; /* the figures as the show ended */
  mr_show_error err;
  /* Layers (issue 23): the frame's show time, the glove clock, arming
   * and punches asked between ticks, and the punch times (-1: none). */
  double t_now;
  mr_clock glove_clock;
  mr_layer layers[MR_SHOW_MAX_GLOVES];
  mr_punch punch;
};
typedef struct mr_show show;

/* One line to the note hook, if there is one. */
void mr_show_note(const show *s, const char *line);
/* What changed about glove g since the user was last told, told once, at
 * the glove's own time now (show_tell.c). */
void mr_show_tell_glove(show *s, size_t g, double now);
/* Frame f's channels that went bad or came back (show_tell.c). */
void mr_show_tell_states(show *s, show_frame *f, const mr_channel_state now[MR_CONTROL_CHANNELS]);

#endif /* MR_SHOW_INTERNAL_H */
