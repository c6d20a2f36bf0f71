/* The watcher's stage (watch_view.h). */
#include "watch_view.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int mr_watch_stage_open(mr_watch_stage *ws, const mr_scene *scene, mr_stage_opts *so, bool window,
                        double fps, char *msg, size_t msg_size, int *usage) {
  memset(ws, 0, sizeof *ws);
  *usage = 0;
  mr_render_def rd = mr_default_render_def();
  rd.headless = !window;
  rd.backend = window ? MR_RENDER_WINDOW : so->backend;
  rd.width = so->width;
  rd.height = so->height;
  rd.gl = so->gl;
  if (so->samples > 0) rd.samples = so->samples;
  mr_window_def wd = mr_default_window_def();
  wd.title = "marionette watch";
  if (mr_stageview_open(&ws->sv, scene, &rd, window ? &wd : NULL, msg, msg_size) != 0) return -1;
  ws->window = window;
  ws->sv.show_osd = false;
  if (mr_stage_opts_apply(so, "watch", &ws->sv) != 0) {
    mr_stageview_close(&ws->sv);
    msg[0] = '\0';
    return *usage = 1, -1;
  }
  if (!mr_stage_opts_writes(so)) return 0;
  char note[200] = "";
  mr_frames_out_def od =
      mr_stage_opts_outputs(so, fps, ws->sv.width, ws->sv.height, note, sizeof note);
  od.keep_time = true;
  if (mr_frames_out_open(&od, &ws->fo, msg, msg_size) != 0) {
    mr_stageview_close(&ws->sv);
    return -1;
  }
  return 0;
}

int mr_watch_stage_draw(mr_watch_stage *ws, double t, const double *xyz, size_t n, char *msg,
                        size_t msg_size) {
  mr_stageview_track(&ws->sv, t, xyz, n);
  mr_stageview_set_time(&ws->sv, t, -1.0);
  if (mr_stageview_draw(&ws->sv, xyz, n, msg, msg_size) != 0) return -1;
  ws->drawn++;
  if (ws->window) {
    mr_render_present(ws->sv.render);
    return 0;
  }
  if (ws->fo == NULL) return 0;
  const uint8_t *rgb = mr_stageview_read(&ws->sv);
  if (rgb == NULL) {
    snprintf(msg, msg_size, "could not read a frame back");
    return -1;
  }
  return mr_frames_out_add(ws->fo, rgb, t, msg, msg_size);
}

void mr_watch_stage_pump(mr_watch_stage *ws) {
  if (!ws->window) return;
  mr_window_event ev;
  while (mr_window_poll(ws->sv.window, &ev) != 0) {
    if (ev.kind == MR_WINDOW_EVENT_QUIT || (ev.kind == MR_WINDOW_EVENT_KEY && ev.down &&
                                            (ev.key == MR_WINDOW_KEY_ESCAPE || ev.key == 'q')))
      ws->quit = true;
    else if (ev.kind == MR_WINDOW_EVENT_MOUSE_MOVE && (ev.buttons & 1))
      mr_stageview_orbit(&ws->sv, -0.3 * ev.dx, 0.3 * ev.dy);
    else if (ev.kind == MR_WINDOW_EVENT_MOUSE_WHEEL)
      mr_stageview_zoom(&ws->sv, ev.dy);
    else if (ev.kind == MR_WINDOW_EVENT_KEY && ev.down && ev.key >= '0' && ev.key <= '8')
      mr_stageview_pick_camera(&ws->sv, ev.key - '1');
  }
}

int mr_watch_stage_close(mr_watch_stage *ws, mr_frames_out_summary *s, char *msg, size_t msg_size) {
  memset(s, 0, sizeof *s);
  int rc = mr_frames_out_close(ws->fo, s, msg, msg_size);
  ws->fo = NULL;
  mr_stageview_close(&ws->sv);
  return rc;
}
