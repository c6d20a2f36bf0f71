/* Commands to a glove whose answers this test writes itself, on a real
 * pty, so that each answer can be wrong on purpose: an ACK or NACK counts
 * only with its command's tag and type; STREAM_OFF lets a quiet glove
 * stay live and STREAM_ON takes that back; tags run 1..255, skipping 0
 * and the tags still remembered, and each goes on the wire as returned;
 * the oldest answered command makes room first, never a pending one. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "glove_wire.h"

typedef struct bench {
  gw_port port;
  mr_glove *g;
  double now;
  gp_decoder wire;    /* what the glove wrote to the port */
  uint8_t tags[1024]; /* the tags of the commands on the wire, in order */
  size_t n_tags;
} bench;

/* A glove on a new port, live, with commands given cmd_timeout and tries. */
static void start(bench *b, double lost_after, double cmd_timeout, int tries) {
  memset(b, 0, sizeof *b);
  gw_port_make(&b->port);
  mr_glove_def d = mr_default_glove_def();
  snprintf(d.source, sizeof d.source, "%s", b->port.source);
  d.lost_after = lost_after;
  d.cmd_timeout = cmd_timeout;
  d.cmd_tries = tries;
  char msg[300];
  if (mr_glove_create(&d, &b->g, msg, sizeof msg) != MR_GLOVE_OK) fail_msg("%s", msg);
  gp_decoder_init(&b->wire, GP_SPEC_HASH);
  b->now = 1.0;
  mr_glove_poll(b->g, b->now, 0);
  gp_msg s = gw_sample(1, 1000u, 0, 2000);
  gw_port_send(&b->port, &s);
  assert_true(gw_poll_for_samples(b->g, b->now) > 0);
}

static void stop(bench *b) {
  mr_glove_destroy(b->g);
  gw_port_remove(&b->port);
}

/* Reads what the glove wrote, keeping each command's tag. */
static void drain(bench *b) {
  struct pollfd p = { b->port.master.fd, POLLIN, 0 };
  while (poll(&p, 1, 0) == 1 && (p.revents & POLLIN)) {
    uint8_t buf[4096];
    ssize_t n = read(b->port.master.fd, buf, sizeof buf);
    if (n <= 0) break;
    for (size_t off = 0; off < (size_t)n;) {
      gp_msg m;
      gp_event ev;
      off += gp_decoder_feed(&b->wire, buf + off, (size_t)n - off, &m, &ev);
      if (ev == GP_EV_FRAME && mr_glove_cmd_name(m.type) != NULL && b->n_tags < sizeof b->tags)
        b->tags[b->n_tags++] = m.u.ping.tag; /* every command's tag comes first */
    }
  }
}

/* Writes m to the glove and polls until it has read it (one more frame). */
static void deliver(bench *b, gp_msg m) {
  mr_glove_counters c0, c;
  mr_glove_get_counters(b->g, &c0);
  gw_port_send(&b->port, &m);
  c = c0;
  for (int i = 0; i < 100 && c.decoder.frames == c0.decoder.frames; i++) {
    mr_glove_poll(b->g, b->now, 10);
    mr_glove_get_counters(b->g, &c);
  }
  assert_int_equal(c.decoder.frames, c0.decoder.frames + 1);
  drain(b);
}

static int send_cmd(bench *b, uint8_t type) {
  mr_glove_cmd cmd = { type, 0, 0 };
  char msg[300];
  int tag = mr_glove_command(b->g, &cmd, b->now, msg, sizeof msg);
  if (tag < 0) fail_msg("%s", msg);
  drain(b);
  return tag;
}

static mr_glove_cmd_state state_of(const bench *b, int tag) {
  return mr_glove_command_result(b->g, tag).state;
}

static void an_answer_counts_only_with_its_commands_tag_and_type(void **state) {
  (void)state;
  bench b;
  start(&b, 0.5, 30.0, 5);
  int ping = send_cmd(&b, GP_PING);
  deliver(&b, gw_answer(GP_ACK, (uint8_t)ping, GP_GET_INFO, 0));
  deliver(&b, gw_answer(GP_NACK, (uint8_t)ping, GP_GET_INFO, GP_NACK_BAD_STATE));
  deliver(&b, gw_answer(GP_ACK, (uint8_t)(ping + 1), GP_PING, 0));
  assert_int_equal(state_of(&b, ping), MR_GLOVE_CMD_PENDING);
  deliver(&b, gw_answer(GP_ACK, (uint8_t)ping, GP_PING, 0));
  assert_int_equal(state_of(&b, ping), MR_GLOVE_CMD_ACKED);

  int save = send_cmd(&b, GP_CAL_SAVE);
  deliver(&b, gw_answer(GP_NACK, (uint8_t)save, GP_CAL_START, GP_NACK_BAD_ARGUMENT));
  deliver(&b, gw_answer(GP_ACK, (uint8_t)save, GP_CAL_CLEAR, 0));
  assert_int_equal(state_of(&b, save), MR_GLOVE_CMD_PENDING);
  deliver(&b, gw_answer(GP_NACK, (uint8_t)save, GP_CAL_SAVE, GP_NACK_BAD_STATE));
  mr_glove_cmd_result r = mr_glove_command_result(b.g, save);
  assert_int_equal(r.state, MR_GLOVE_CMD_NACKED);
  assert_int_equal(r.nack_reason, GP_NACK_BAD_STATE);
  assert_int_equal(r.type, GP_CAL_SAVE);
  assert_int_equal(r.sends, 1);
  /* A late ACK for it changes nothing: it was answered. */
  deliver(&b, gw_answer(GP_ACK, (uint8_t)save, GP_CAL_SAVE, 0));
  assert_int_equal(state_of(&b, save), MR_GLOVE_CMD_NACKED);
  stop(&b);
}

/* lost_after 0.3 s. After STREAM_OFF's ACK a glove quiet for 1 s (it
 * sends INFO once a second) is still live; after STREAM_ON's, quiet for
 * 0.35 s, it is lost. */
static void stream_on_takes_back_what_stream_off_allowed_a_quiet_glove(void **state) {
  (void)state;
  bench b;
  start(&b, 0.3, 30.0, 5);
  int off = send_cmd(&b, GP_STREAM_OFF);
  deliver(&b, gw_answer(GP_ACK, (uint8_t)off, GP_STREAM_OFF, 0));
  assert_int_equal(state_of(&b, off), MR_GLOVE_CMD_ACKED);
  mr_glove_poll(b.g, b.now += 1.0, 0);
  assert_int_equal(mr_glove_get_state(b.g), MR_GLOVE_LIVE);
  int on = send_cmd(&b, GP_STREAM_ON);
  deliver(&b, gw_answer(GP_ACK, (uint8_t)on, GP_STREAM_ON, 0));
  assert_int_equal(state_of(&b, on), MR_GLOVE_CMD_ACKED);
  mr_glove_poll(b.g, b.now + 0.25, 0);
  assert_int_equal(mr_glove_get_state(b.g), MR_GLOVE_LIVE);
  mr_glove_poll(b.g, b.now + 0.35, 0);
  assert_int_equal(mr_glove_get_state(b.g), MR_GLOVE_LOST);
  stop(&b);
}

/* 600 commands, each answered but the fifth, which stays pending: tags
 * run 1..255 and again from 1, never 0, skipping 5 while it is
 * remembered; each goes on the wire under the tag returned. */
static void tags_skip_0_when_they_wrap_and_skip_the_tags_still_remembered(void **state) {
  (void)state;
  bench b;
  start(&b, 60.0, 60.0, 100);
  int want = 1, pending = -1;
  for (int k = 0; k < 600; k++) {
    int tag = send_cmd(&b, GP_PING);
    if (tag != want) fail_msg("command %d has tag %d, expected %d", k, tag, want);
    if (k == 4)
      pending = tag;
    else
      deliver(&b, gw_answer(GP_ACK, (uint8_t)tag, GP_PING, 0));
    do want = want == 255 ? 1 : want + 1;
    while (want == pending);
    b.now += 0.001;
  }
  assert_int_equal(pending, 5);
  assert_int_equal(state_of(&b, pending), MR_GLOVE_CMD_PENDING);
  assert_int_equal(b.n_tags, 600);
  want = 1;
  for (size_t k = 0; k < b.n_tags; k++) {
    if (b.tags[k] != want) fail_msg("command %zu went out as tag %u, not %d", k, b.tags[k], want);
    do want = want == 255 ? 1 : want + 1;
    while (want == pending && k >= 4);
  }
  stop(&b);
}

/* Sixteen commands, answered newest first, the first left pending: a new
 * command takes the place of the oldest answered (the second), then the
 * next oldest, whatever the order of their slots; the pending one stays
 * until it is answered. Sixteen pending: no room, said so. */
static void the_oldest_answered_command_makes_room_first(void **state) {
  (void)state;
  bench b;
  start(&b, 60.0, 60.0, 100);
  int t[40];
  for (int i = 1; i <= 16; i++) t[i] = send_cmd(&b, GP_PING);
  for (int i = 16; i >= 2; i--) deliver(&b, gw_answer(GP_ACK, (uint8_t)t[i], GP_PING, 0));
  t[17] = send_cmd(&b, GP_PING);
  assert_int_equal(state_of(&b, t[2]), MR_GLOVE_CMD_UNKNOWN);
  assert_int_equal(state_of(&b, t[1]), MR_GLOVE_CMD_PENDING);
  assert_int_equal(state_of(&b, t[3]), MR_GLOVE_CMD_ACKED);
  t[18] = send_cmd(&b, GP_PING);
  assert_int_equal(state_of(&b, t[3]), MR_GLOVE_CMD_UNKNOWN);
  /* 17 answered, in the first slot freed; still 4 is older. */
  deliver(&b, gw_answer(GP_ACK, (uint8_t)t[17], GP_PING, 0));
  t[19] = send_cmd(&b, GP_PING);
  assert_int_equal(state_of(&b, t[4]), MR_GLOVE_CMD_UNKNOWN);
  assert_int_equal(state_of(&b, t[17]), MR_GLOVE_CMD_ACKED);
  /* 1 answered at last: now the oldest of all. */
  deliver(&b, gw_answer(GP_ACK, (uint8_t)t[1], GP_PING, 0));
  t[20] = send_cmd(&b, GP_PING);
  assert_int_equal(state_of(&b, t[1]), MR_GLOVE_CMD_UNKNOWN);
  assert_int_equal(state_of(&b, t[5]), MR_GLOVE_CMD_ACKED);
  /* Twelve more take the places of 5 .. 16; then 17's; then none is left. */
  for (int i = 21; i <= 33; i++) t[i] = send_cmd(&b, GP_PING);
  assert_int_equal(state_of(&b, t[17]), MR_GLOVE_CMD_UNKNOWN);
  mr_glove_cmd cmd = { GP_PING, 0, 0 };
  char msg[300], want[300];
  assert_int_equal(mr_glove_command(b.g, &cmd, b.now, msg, sizeof msg), -1);
  snprintf(want, sizeof want, "glove %s: 16 commands are already waiting for an answer",
           b.port.source);
  assert_string_equal(msg, want);
  for (int i = 18; i <= 33; i++) assert_int_equal(state_of(&b, t[i]), MR_GLOVE_CMD_PENDING);
  stop(&b);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(an_answer_counts_only_with_its_commands_tag_and_type),
    cmocka_unit_test(stream_on_takes_back_what_stream_off_allowed_a_quiet_glove),
    cmocka_unit_test(tags_skip_0_when_they_wrap_and_skip_the_tags_still_remembered),
    cmocka_unit_test(the_oldest_answered_command_makes_room_first),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
