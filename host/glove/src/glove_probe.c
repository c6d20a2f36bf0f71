/* Listening for a glove: mr_glove_probe on one port, and serial:auto's
 * search of every USB serial port for the glove it was given. */
#include <stdio.h>
#include <string.h>

#include "glove_internal.h"

/* serial:auto: the first serial port whose glove announces itself (with
 * the uid seen before, once there was one), into g->spec. 0 or −1. */
int mr_glove_find(mr_glove *g) {
  mr_serial_info ports[32];
  size_t n = 0;
  mr_io_error err;
  if (mr_serial_list(ports, 32, &n, &err) != 0) {
    snprintf(g->last_error, sizeof g->last_error, "%s", err.msg);
    return -1;
  }
  size_t usb = 0;
  for (size_t i = 0; i < n && i < 32; i++) {
    if (!ports[i].is_usb) continue; /* a glove comes over USB */
    usb++;
    char src[MR_GLOVE_SOURCE_MAX];
    snprintf(src, sizeof src, "serial:%.200s", ports[i].name);
    gp_info info;
    bool foreign = false;
    if (mr_glove_probe(src, 1.5, &info, &foreign, NULL, 0) != 1) continue;
    if (g->have_uid && memcmp(info.uid, g->uid, sizeof g->uid) != 0) continue;
    memcpy(g->uid, info.uid, sizeof g->uid);
    g->have_uid = true;
    snprintf(g->spec, sizeof g->spec, "%s", src);
    return 0;
  }
  snprintf(g->last_error, sizeof g->last_error, "no glove%s on any of %zu USB serial ports",
           g->have_uid ? " of the same uid" : "", usb);
  return -1;
}

int mr_glove_probe(const char *source, double wait_s, gp_info *info, bool *foreign, char *msg,
                   size_t msg_size) {
  char spec[MR_GLOVE_SOURCE_MAX + 16], dummy[8];
  if (msg == NULL || msg_size == 0) {
    msg = dummy;
    msg_size = sizeof dummy;
  }
  if (foreign != NULL) *foreign = false;
  if (source == NULL || mr_glove_io_spec(source, spec, sizeof spec) != 0) {
    snprintf(msg, msg_size, "glove source '%s': not a port to probe", source ? source : "");
    return -1;
  }
  mr_io io;
  mr_io_error err;
  if (mr_io_open(&io, spec, MR_IO_READ, &err) != 0) {
    snprintf(msg, msg_size, "%s", err.msg);
    return -1;
  }
  gp_decoder dec;
  gp_decoder_init(&dec, GP_SPEC_HASH);
  int found = 0;
  uint64_t end = mr_io_monotonic_ns() + (uint64_t)(wait_s * 1e9);
  /* INFO comes first and then once a second: 1.5 s sees one. */
  while (!found && mr_io_monotonic_ns() < end) {
    uint8_t buf[512];
    size_t got = 0;
    mr_io_status st = mr_io_read(&io, buf, sizeof buf, 50, &got, &err);
    for (size_t off = 0; off < got && !found;) {
      gp_msg m;
      gp_event ev;
      off += gp_decoder_feed(&dec, buf + off, got - off, &m, &ev);
      if ((ev == GP_EV_FRAME || ev == GP_EV_SPEC_MISMATCH) && m.type == GP_INFO) {
        if (info != NULL) *info = m.u.info;
        if (foreign != NULL) *foreign = ev == GP_EV_SPEC_MISMATCH;
        found = 1;
      }
    }
    if (st == MR_IO_EOF || st == MR_IO_HANGUP || mr_io_failed(st)) break;
  }
  mr_io_close(&io);
  if (!found) snprintf(msg, msg_size, "%s: no glove announced itself in %.1f s", source, wait_s);
  return found;
}
