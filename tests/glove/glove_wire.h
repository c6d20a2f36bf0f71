/* What a glove sends, for the glove tests: frames built with the
 * protocol's own encoder and written to a real descriptor (a pty master, a
 * socket), and a glove made from a source with a few settings. */
#ifndef GLOVE_WIRE_H
#define GLOVE_WIRE_H

#include <stddef.h>
#include <stdint.h>

#include "mr_glove.h"

/* A SAMPLE: every channel raw + 100 k. */
gp_msg gw_sample(uint16_t seq, uint32_t t_us, uint16_t flags, uint16_t raw);
/* An INFO of our definition: uid, calibration state and range, ADC bits. */
gp_msg gw_info(uint32_t uid, uint8_t cal_state, uint16_t cal_min, uint16_t cal_max,
               uint8_t adc_bits);
/* An ACK (nack_reason 0) or a NACK. */
gp_msg gw_answer(uint8_t type, uint8_t tag, uint8_t cmd, uint8_t nack_reason);

/* m encoded with our spec hash into wire (GP_MAX_WIRE bytes); its length. */
size_t gw_encode(const gp_msg *m, uint8_t *wire);
/* Writes every byte of buf to fd within 2 s; 0, or -1 (the peer left). */
int gw_write(int fd, const void *buf, size_t len);
/* gw_encode + gw_write; the bytes written, or 0 when the peer left. */
size_t gw_send(int fd, const gp_msg *m);

/* A glove's port: a real pty reached through a symlink, as udev names a
 * glove, so that a replug (a new pty) keeps the name. */
typedef struct gw_port {
  mr_io master;
  char dir[64], link[96], source[128]; /* source: "pty:LINK" */
} gw_port;
void gw_port_make(gw_port *p); /* a folder for the link, and a first pty */
void gw_port_plug(gw_port *p);
void gw_port_unplug(gw_port *p);
void gw_port_remove(gw_port *p); /* unplugged, the folder gone */
/* gw_send through the port; fails the test unless every byte went. */
size_t gw_port_send(gw_port *p, const gp_msg *m);

/* A glove on source with lost_after and retry_every (s) as given; fails
 * the test if it cannot be made. */
mr_glove *gw_glove(const char *source, double lost_after, double retry_every);

/* Polls at `now` (real waits of 10 ms) until a SAMPLE is taken or a second
 * of real time passed: how many were taken. */
int gw_poll_for_samples(mr_glove *g, double now);

/* A take of `count` SAMPLEs (seq 1, 2, ..., raw 2000), one chunk each,
 * `spacing` s apart from t = 0 on both clocks, written to a scratch file:
 * the file's bytes (free them) and their count. */
char *gw_take(int count, double spacing, size_t *len);

/* "ms late" as the theater shows it, s. */
double gw_lateness(const mr_glove *g);

#endif
