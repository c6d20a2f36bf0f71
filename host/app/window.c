/* A live show on the stage: the window's keys, mouse and gamepad, the
 * on-screen display, and the frames drawn, shown or written (issue 10,
 * items 4 and 5). Pause, single step, slow motion and reset go to the
 * show's runner as commands; its clock acts on them (host/theater). */
#define _POSIX_C_SOURCE 200809L

#include "window.h"

#include "stage_opts.h"
#include "takes_osd.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define ORBIT_DEG 0.3 /* degrees of orbit per pixel dragged */
#define DAY_STEP  0.02

static double wall(const mr_live *lv) {
  return lv->wall.now(lv->wall.self);
}

static int key_named(const char *name) {
  static const struct {
    const char *name;
    int key;
  } names[] = { { "space", MR_WINDOW_KEY_SPACE },  { "esc", MR_WINDOW_KEY_ESCAPE },
                { "left", MR_WINDOW_KEY_LEFT },    { "right", MR_WINDOW_KEY_RIGHT },
                { "up", MR_WINDOW_KEY_UP },        { "down", MR_WINDOW_KEY_DOWN },
                { "pgup", MR_WINDOW_KEY_PAGE_UP }, { "pgdn", MR_WINDOW_KEY_PAGE_DOWN },
                { "f1", MR_WINDOW_KEY_F1 },        { "f2", MR_WINDOW_KEY_F1 + 1 },
                { "f3", MR_WINDOW_KEY_F1 + 2 },    { "f4", MR_WINDOW_KEY_F1 + 3 },
                { "f5", MR_WINDOW_KEY_F1 + 4 },    { "f6", MR_WINDOW_KEY_F1 + 5 },
                { "f7", MR_WINDOW_KEY_F1 + 6 },    { "f8", MR_WINDOW_KEY_F1 + 7 },
                { "f9", MR_WINDOW_KEY_F1 + 8 },    { "f10", MR_WINDOW_KEY_F1 + 9 },
                { "f11", MR_WINDOW_KEY_F11 },      { "f12", MR_WINDOW_KEY_F12 } };
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
    if (strcmp(name, names[i].name) == 0) return names[i].key;
  if (strlen(name) == 1 && name[0] > ' ' && name[0] < 127) return name[0];
  return -1;
}

int mr_live_parse_keys(mr_live *lv, const char *list) {
  char buf[1024];
  if (strlen(list) >= sizeof buf) return -1; /* never parse a cut-short list */
  snprintf(buf, sizeof buf, "%s", list);
  for (char *save = NULL, *item = strtok_r(buf, ",", &save); item != NULL;
       item = strtok_r(NULL, ",", &save)) {
    char *colon = strchr(item, ':'), *end = NULL;
    if (colon == NULL || lv->n_keys == MR_KEYS_MAX) return -1;
    *colon = '\0';
    mr_key_press k = { strtod(item, &end), 0.05, 0, false, false };
    if (end == item || *end != '\0' || !(k.t >= 0)) return -1;
    char *slash = strchr(colon + 1, '/');
    if (slash != NULL) {
      *slash = '\0';
      k.hold = strtod(slash + 1, &end);
      if (end == slash + 1 || *end != '\0' || !(k.hold > 0)) return -1;
    }
    if ((k.key = key_named(colon + 1)) < 0) return -1;
    lv->keys[lv->n_keys++] = k;
  }
  return lv->n_keys > 0 ? 0 : -1;
}

static void send(mr_live *lv, mr_show_cmd cmd) {
  if (lv->runner != NULL) mr_show_runner_send(lv->runner, cmd);
}

static void toggle_pause(mr_live *lv) {
  lv->paused = !lv->paused;
  lv->pause_wall = wall(lv);
  send(lv, MR_SHOW_CMD_PAUSE);
}

/* The take keys: F2-F6 arm or disarm the selected glove's thumb, index,
 * middle, ring and little finger; F7 selects the next glove; F8 punches
 * in or out; F9 and F10 step to the previous or next take beneath, which
 * ends this show (the program starts the next over that take). Whether
 * one was taken. */
static bool take_key(mr_live *lv, int key) {
  int f = key - MR_WINDOW_KEY_F1 + 1;
  if (f < 2 || f > 10) return false;
  if (f <= 6) {
    size_t g = lv->glove_sel;
    lv->armed[g] ^= 1u << (f - 2);
    if (lv->runner != NULL) mr_show_runner_send_arm(lv->runner, g, lv->armed[g]);
  } else if (f == 7) {
    lv->glove_sel = (lv->glove_sel + 1) % (lv->n_gloves > 0 ? lv->n_gloves : 1);
  } else if (f == 8) {
    send(lv, MR_SHOW_CMD_PUNCH);
  } else {
    lv->take_step = f == 9 ? -1 : 1;
    send(lv, MR_SHOW_CMD_QUIT);
  }
  return true;
}

/* The stage's keys (the man page's table). */
static void stage_key(mr_live *lv, int key) {
  mr_stageview *sv = &lv->sv;
  if (take_key(lv, key)) {
  } else if (key == ' ') {
    toggle_pause(lv);
  } else if (key == '.') {
    if (!lv->paused) lv->pause_wall = wall(lv);
    lv->paused = true;
    send(lv, MR_SHOW_CMD_STEP);
  } else if (key == 's') {
    lv->speed = mr_show_speed_next(lv->speed);
    send(lv, MR_SHOW_CMD_SPEED);
  } else if (key == 'r') {
    send(lv, MR_SHOW_CMD_RESET);
  } else if (key == 'n') {
    mr_stageview_set_day(sv, sv->time_of_day + 0.5);
  } else if (key == 'm') {
    mr_stageview_next_material(sv);
  } else if (key == 'c') {
    mr_stage_show_spheres(sv->stage, !mr_stage_get_def(sv->stage)->show_spheres);
  } else if (key == '[' || key == ']') {
    mr_stageview_set_day(sv, sv->time_of_day + (key == ']' ? DAY_STEP : -DAY_STEP));
  } else if (key == 'h' || key == MR_WINDOW_KEY_F1) {
    sv->show_osd = !sv->show_osd;
  } else if (key == 'p' || key == MR_WINDOW_KEY_F12) {
    lv->shot_asked = true;
  } else if ((key == 'f' || key == MR_WINDOW_KEY_F11) && lv->window) {
    if (mr_window_set_fullscreen(sv->window, !lv->fullscreen) == MR_WINDOW_OK)
      lv->fullscreen = !lv->fullscreen;
  } else if (key == 'q' || key == MR_WINDOW_KEY_ESCAPE) {
    /* The first asks for the curtain to close; a second, for no wait. */
    if (lv->quit) lv->quit_now = true;
    lv->quit = true;
  } else if (key >= '0' && key <= '9') {
    mr_stageview_pick_camera(sv, key - '1'); /* 0: -1, the orbit camera */
  }
}

void mr_live_event(mr_live *lv, const mr_window_event *ev) {
  if (lv->manual_on && mr_manual_event(&lv->manual, ev)) return;
  switch (ev->kind) {
  case MR_WINDOW_EVENT_QUIT: /* the window closed: nothing left to watch */
    lv->quit = lv->quit_now = true;
    break;
  case MR_WINDOW_EVENT_KEY:
    if (ev->down) stage_key(lv, ev->key);
    break;
  case MR_WINDOW_EVENT_MOUSE_BUTTON:
    if (ev->button == 1) lv->dragging = ev->down;
    break;
  case MR_WINDOW_EVENT_MOUSE_MOVE:
    if (ev->buttons & 1) mr_stageview_orbit(&lv->sv, -ev->dx * ORBIT_DEG, ev->dy * ORBIT_DEG);
    break;
  case MR_WINDOW_EVENT_MOUSE_WHEEL:
    mr_stageview_zoom(&lv->sv, ev->dy);
    break;
  default:
    break;
  }
}

/* Scripted keys whose time has come, on show time (the frames' own,
 * which falls behind the clock when renders are skipped and lag is given
 * up). Paused, show time stands still, so the script's time runs on the
 * wall clock from the pause: a script can let go of its own pause. */
static int play_keys(mr_live *lv) {
  int played = 0;
  double now = lv->show_t + (lv->paused ? wall(lv) - lv->pause_wall : 0.0);
  for (int i = 0; i < lv->n_keys; i++) {
    /* A screenshot shows the frame as the keys before it left it: on a
     * slow box several keys fall due between two frames, and a later one
     * (m, say) would otherwise reach the shot, or a second p be lost. */
    if (lv->shot_asked) break;
    mr_key_press *k = &lv->keys[i];
    mr_window_event ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = MR_WINDOW_EVENT_KEY;
    ev.key = k->key;
    if (!k->down_sent && now >= k->t) {
      k->down_sent = ev.down = true;
      mr_live_event(lv, &ev);
      played++;
    }
    if (k->down_sent && !k->up_sent && now >= k->t + k->hold) {
      /* A press and its release may come in one pass: the release must
       * not go out as a second press. */
      k->up_sent = true;
      ev.down = false;
      mr_live_event(lv, &ev);
      played++;
    }
  }
  return played;
}

int mr_live_pump(mr_live *lv) {
  mr_window_event ev;
  int events = 0;
  if (lv->window)
    while (mr_window_poll(lv->sv.window, &ev) != 0) {
      mr_live_event(lv, &ev);
      events++;
    }
  events += play_keys(lv);
  if (!lv->manual_on) return events;
  double w = wall(lv);
  mr_manual_update(&lv->manual, lv->last_pump > 0 ? w - lv->last_pump : 0);
  lv->last_pump = w;
  /* Paused, the show reads nothing: samples would only pile up. */
  if (!lv->paused) mr_pty_glove_pump(&lv->glove, lv->manual.values, w);
  return events;
}

int mr_live_screenshot(mr_live *lv) {
  const uint8_t *rgb = mr_stageview_read(&lv->sv);
  char path[700];
  snprintf(path, sizeof path, "%s/shot_%03d.png", lv->shot_dir[0] ? lv->shot_dir : ".", lv->shots);
  if (rgb == NULL || mr_png_write(path, rgb, lv->sv.width, lv->sv.height) != 0) {
    fprintf(stderr, "marionette run: could not write the screenshot %s\n", path);
    return -1;
  }
  lv->shots++;
  fprintf(stderr, "marionette run: screenshot %s\n", path);
  return 0;
}

/* The figures of the status line, over the latest second: fps is frames
 * drawn here, on the stage. */
static void osd_rates(mr_live *lv, const mr_scheduler_stats *s) {
  double w = wall(lv);
  if (lv->osd_wall == 0) {
    lv->osd_wall = w;
    lv->osd_drawn = lv->drawn;
    lv->osd_sim = s->sim_time;
    lv->osd_steps = s->steps;
    return;
  }
  if (w - lv->osd_wall < 1.0) return;
  lv->fps = (double)(lv->drawn - lv->osd_drawn) / (w - lv->osd_wall);
  if (s->steps > lv->osd_steps)
    lv->dt_mean = (s->sim_time - lv->osd_sim) / (double)(s->steps - lv->osd_steps);
  lv->osd_wall = w;
  lv->osd_drawn = lv->drawn;
  lv->osd_sim = s->sim_time;
  lv->osd_steps = s->steps;
}

void mr_live_set_takes(mr_live *lv, const char *beneath) {
  snprintf(lv->beneath, sizeof lv->beneath, "%s", beneath != NULL ? beneath : "");
  lv->armed_seen = false;
}

static void osd_lines(mr_live *lv, const mr_show_frame *f) {
  mr_stageview *sv = &lv->sv;
  const mr_scheduler_stats s = f->stats;
  osd_rates(lv, &s);
  uint64_t skipped = s.frames_simulated > lv->drawn ? s.frames_simulated - lv->drawn : 0;
  mr_stageview_osd_clear(sv);
  const mr_takes_osd to = { lv->speed, f->recording, lv->beneath, lv->glove_sel };
  char text[MR_OSD_LINE_MAX];
  mr_takes_osd_marks(&to, text, sizeof text);
  mr_stageview_osd(sv, "t %.2f s  %.0f fps  dt %.1f ms%s%s", f->t, lv->fps, lv->dt_mean * 1e3,
                   lv->paused ? "  PAUSED" : "", text);
  mr_takes_osd_beneath(&to, text, sizeof text);
  if (text[0] != '\0')
    mr_stageview_osd(sv, "%s  lag %.0f ms  skip %llu", text, s.latency_p50 * 1e3,
                     (unsigned long long)skipped);
  else
    mr_stageview_osd(sv, "lag %.0f/%.0f ms  skip %llu  resets %llu", s.latency_p50 * 1e3,
                     s.latency_p99 * 1e3, (unsigned long long)skipped,
                     (unsigned long long)s.resets);
  /* The overlay is MR_OSD_ROWS lines: the first gloves get one each. */
  for (size_t g = 0; g < f->n_gloves && g < MR_OSD_ROWS - 3; g++) {
    const mr_show_glove_view *v = &f->gloves[g];
    const mr_glove_reading r = v->reading;
    double late = r.host_t - r.device_t - v->clock_offset;
    char lateness[48] = "";
    if (r.samples > 0 && isfinite(late))
      snprintf(lateness, sizeof lateness, " %.0f ms late", late * 1e3);
    if (v->layered) {
      mr_takes_osd_glove(&to, g, v->armed, text, sizeof text);
      mr_stageview_osd(sv, "%s%s", text, lateness);
      continue;
    }
    mr_stageview_osd(sv, "glove %zu%s %s%s", g + 1, lv->manual_on && g == 0 ? " keys" : "",
                     mr_glove_state_name(v->state), lateness);
  }
  const char *cam = sv->camera >= 0 ? sv->scene->stage.cameras[sv->camera].name : "orbit";
  mr_stageview_osd(sv, "%s  day %.2f  h hides, %s", cam, sv->time_of_day,
                   lv->closing ? "q: at once" : "q quits");
}

bool mr_live_should_quit(mr_live *lv) {
  if (lv->failed || lv->quit_now) return true;
  if (!lv->quit) return false;
  const mr_curtain_def *c = &lv->sv.scene->stage.curtain;
  if (!c->show || !(c->close_s > 0)) return true;
  if (!lv->closing) {
    lv->closing = true;
    lv->closing_wall = wall(lv);
    double end = lv->show_t + c->close_s;
    if (lv->curtain_end < 0 || end < lv->curtain_end) lv->curtain_end = end;
    if (lv->paused) toggle_pause(lv);
  }
  /* Slow motion plays it at a quarter of the speed. */
  return lv->show_t >= lv->curtain_end || wall(lv) - lv->closing_wall > 4 * c->close_s + 1;
}

void mr_live_present(mr_live *lv, const mr_show_frame *f) {
  if (lv->failed) return;
  lv->show_t = f->t;
  lv->n_gloves = f->n_gloves;
  if (!lv->armed_seen) {
    for (size_t g = 0; g < f->n_gloves; g++) lv->armed[g] = f->gloves[g].armed;
    lv->armed_seen = true;
  }
  mr_stageview_set_time(&lv->sv, f->t, lv->curtain_end);
  mr_stageview_track(&lv->sv, f->t, f->xyz, (size_t)f->n_particles);
  osd_lines(lv, f);
  if (mr_stageview_draw(&lv->sv, f->xyz, (size_t)f->n_particles, lv->msg, sizeof lv->msg) != 0) {
    lv->failed = lv->quit = true;
    return;
  }
  lv->drawn++;
  if (lv->shot_asked) {
    lv->shot_asked = false;
    mr_live_screenshot(lv);
  }
  if (lv->window) {
    mr_render_present(lv->sv.render);
    return;
  }
  if (lv->fo == NULL) return;
  const uint8_t *rgb = mr_stageview_read(&lv->sv);
  double t = lv->pass_t0 + f->t;
  if (rgb == NULL || mr_frames_out_add(lv->fo, rgb, t, lv->msg, sizeof lv->msg) != 0) {
    if (rgb == NULL) snprintf(lv->msg, sizeof lv->msg, "could not read a frame back");
    lv->failed = lv->quit = true;
  }
}

void mr_live_redraw(mr_live *lv) {
  if (lv->failed || !lv->window || lv->drawn == 0) return;
  if (mr_stageview_redraw(&lv->sv, lv->msg, sizeof lv->msg) != 0) {
    lv->failed = lv->quit = true;
    return;
  }
  if (lv->shot_asked) mr_live_screenshot(lv);
  lv->shot_asked = false;
  mr_render_present(lv->sv.render);
}

void mr_live_hold(mr_live *lv, double t) {
  t += lv->pass_t0;
  if (lv->fo != NULL && !lv->failed && mr_frames_out_hold(lv->fo, t, lv->msg, sizeof lv->msg) != 0)
    lv->failed = true;
}

void mr_live_next_pass(mr_live *lv, double end) {
  mr_live_hold(lv, end);
  lv->pass_t0 += end > 0 ? end : 0;
}

static int open_outputs(mr_live *lv, const mr_live_def *def, mr_stage_opts *so, char *msg,
                        size_t msg_size) {
  lv->out = so->out;
  snprintf(lv->shot_dir, sizeof lv->shot_dir, "%s", so->out != NULL ? so->out : ".");
  if (so->out != NULL && mr_make_dir(so->out) != 0) {
    snprintf(msg, msg_size, "cannot make the folder %s", so->out);
    return -1;
  }
  if (lv->window || !mr_stage_opts_writes(so)) return 0;
  char note[200];
  mr_frames_out_def od =
      mr_stage_opts_outputs(so, def->fps, lv->sv.width, lv->sv.height, note, sizeof note);
  od.keep_time = true; /* skipped renders must not shorten the video */
  if (note[0] != '\0') fprintf(stderr, "marionette run: %s\n", note);
  return mr_frames_out_open(&od, &lv->fo, msg, msg_size);
}

int mr_live_open(mr_live *lv, const mr_scene *scene, const mr_live_def *def,
                 struct mr_stage_opts *so, int *usage, char *msg, size_t msg_size) {
  *usage = 0;
  lv->wall = mr_clock_wall();
  lv->window = def->window;
  lv->curtain_end = def->end > 0 ? def->end : -1;
  lv->fullscreen = def->fullscreen;
  lv->speed = def->speed > 0 ? def->speed : 1.0;
  if (def->keys != NULL && mr_live_parse_keys(lv, def->keys) != 0) {
    snprintf(msg, msg_size,
             "expected --keys T:KEY[/HOLD],... (KEY a character, space, esc, left, right, up, "
             "down, pgup, pgdn or f1 to f12), got '%s'",
             def->keys);
    return *usage = 1, -1;
  }
  mr_render_def rd = mr_default_render_def();
  rd.headless = !def->window;
  rd.backend = def->window ? MR_RENDER_WINDOW : so->backend;
  if (def->window && so->backend != MR_RENDER_AUTO && so->backend != MR_RENDER_WINDOW)
    rd.backend = so->backend;
  rd.width = so->width;
  rd.height = so->height;
  rd.gl = so->gl;
  if (so->samples > 0) rd.samples = so->samples;
  mr_window_def wd = mr_default_window_def();
  wd.fullscreen = def->fullscreen;
  wd.title = "marionette";
  if (mr_stageview_open(&lv->sv, scene, &rd, &wd, msg, msg_size) != 0) return -1;
  if (mr_stage_opts_apply(so, "run", &lv->sv) != 0) {
    mr_stageview_close(&lv->sv);
    msg[0] = '\0'; /* the line is out */
    return *usage = 1, -1;
  }
  if (open_outputs(lv, def, so, msg, msg_size) != 0) {
    mr_stageview_close(&lv->sv);
    return -1;
  }
  lv->sv.show_osd = !def->no_osd;
  lv->manual_on = def->manual;
  mr_manual_init(&lv->manual);
  if (def->manual) {
    if (mr_pty_glove_open(&lv->glove, 100, wall(lv), msg, msg_size) != 0) {
      mr_live_close(lv, true);
      return -1;
    }
    snprintf(lv->glove_source, sizeof lv->glove_source, "pty:%s", mr_io_path(&lv->glove.io));
  }
  return 0;
}

int mr_live_close(mr_live *lv, bool quiet) {
  mr_frames_out_summary s;
  char msg[700] = "";
  int rc = mr_frames_out_close(lv->fo, &s, msg, sizeof msg);
  lv->fo = NULL;
  if (!quiet || rc != 0) {
    mr_render_backend b = mr_render_backend_of(lv->sv.render);
    printf("stage: %s (%s), %dx%d, %llu frames drawn (%s)\n",
           lv->window ? "in a window" : "headless",
           b == MR_RENDER_WINDOW ? "SDL" : mr_render_backend_name(b), lv->sv.width, lv->sv.height,
           (unsigned long long)lv->drawn, mr_render_gl_version(lv->sv.render));
    if (s.frames > 0 || s.pngs > 0) {
      if (lv->out != NULL) printf("png frames: %llu in %s\n", (unsigned long long)s.pngs, lv->out);
      if (s.sheet_cells > 0) printf("sheet: %d thumbnails\n", s.sheet_cells);
      if (s.encoded > 0) printf("mp4: %llu frames\n", (unsigned long long)s.encoded);
    }
    if (lv->shots > 0) printf("screenshots: %d in %s\n", lv->shots, lv->shot_dir);
    if (lv->manual_on)
      printf("keys glove: %llu samples sent\n", (unsigned long long)lv->glove.samples);
  }
  if (rc != 0) fprintf(stderr, "marionette run: %s\n", msg);
  if (lv->failed) fprintf(stderr, "marionette run: %s\n", lv->msg);
  mr_pty_glove_close(&lv->glove);
  mr_stageview_close(&lv->sv);
  return rc != 0 || lv->failed ? -1 : 0;
}
