/* Commands to a glove (protocol/SPEC.md, 6): each under a tag of its own,
 * sent again every cmd_timeout until the glove answers with that tag. The
 * wire bytes are kept, so a retry is the same frame; the glove acts on a
 * repeated command again, which every command here allows (each sets a
 * state rather than stepping one). */
#include <stdio.h>
#include <string.h>

#include "glove_internal.h"

const char *mr_glove_cmd_name(uint8_t type) {
  switch (type) {
  case GP_PING:
    return "PING";
  case GP_GET_INFO:
    return "GET_INFO";
  case GP_SET_RATE:
    return "SET_RATE";
  case GP_STREAM_ON:
    return "STREAM_ON";
  case GP_STREAM_OFF:
    return "STREAM_OFF";
  case GP_CAL_START:
    return "CAL_START";
  case GP_CAL_SAVE:
    return "CAL_SAVE";
  case GP_CAL_CLEAR:
    return "CAL_CLEAR";
  case GP_GET_STATUS:
    return "GET_STATUS";
  default:
    return NULL;
  }
}

const char *mr_glove_nack_reason_name(uint8_t reason) {
  switch (reason) {
  case GP_NACK_UNKNOWN_COMMAND:
    return "UNKNOWN_COMMAND";
  case GP_NACK_BAD_LENGTH:
    return "BAD_LENGTH";
  case GP_NACK_BAD_ARGUMENT:
    return "BAD_ARGUMENT";
  case GP_NACK_BAD_STATE:
    return "BAD_STATE";
  case GP_NACK_FLASH_ERROR:
    return "FLASH_ERROR";
  default:
    return "an unknown reason";
  }
}

/* A slot for a new command: a free one, else the oldest answered. */
static mr_glove_pending *slot(mr_glove *g) {
  mr_glove_pending *best = NULL;
  for (int i = 0; i < MR_GLOVE_MAX_PENDING; i++) {
    mr_glove_pending *p = &g->cmds[i];
    if (!p->used) return p;
    if (p->result.state != MR_GLOVE_CMD_PENDING && (best == NULL || p->serial < best->serial))
      best = p;
  }
  return best;
}

static bool tag_in_use(const mr_glove *g, uint8_t tag) {
  for (int i = 0; i < MR_GLOVE_MAX_PENDING; i++)
    if (g->cmds[i].used && g->cmds[i].result.tag == tag) return true;
  return false;
}

/* 1..255, skipping tags still remembered, so an answer is never taken for
 * another command's. Tag 0 is left out: a NACK for a command that came
 * with no payload carries it. */
static uint8_t fresh_tag(mr_glove *g) {
  for (int k = 0; k < 255; k++) {
    uint8_t t = g->next_tag;
    g->next_tag = (uint8_t)(g->next_tag == 255 ? 1 : g->next_tag + 1);
    if (!tag_in_use(g, t)) return t;
  }
  return g->next_tag;
}

static size_t encode(const mr_glove_cmd *c, uint8_t tag, uint8_t *wire) {
  gp_msg m;
  memset(&m, 0, sizeof m);
  m.type = c->type;
  if (c->type == GP_SET_RATE) {
    m.u.set_rate.tag = tag;
    m.u.set_rate.frame_rate_hz = c->frame_rate_hz;
    m.u.set_rate.baud = c->baud;
  } else {
    m.u.ping.tag = tag; /* every other command is its tag alone */
  }
  return gp_encode(&m, GP_SPEC_HASH, wire, GP_MAX_WIRE);
}

int mr_glove_command(mr_glove *g, const mr_glove_cmd *cmd, double now, char *msg, size_t msg_size) {
  char dummy[8];
  if (msg == NULL || msg_size == 0) {
    msg = dummy;
    msg_size = sizeof dummy;
  }
  if (g == NULL || cmd == NULL || mr_glove_cmd_name(cmd->type) == NULL) {
    snprintf(msg, msg_size, "expected a glove and a command (PING .. GET_STATUS)");
    return -1;
  }
  if (!g->writable) {
    snprintf(msg, msg_size,
             "glove %s: %s cannot be sent: a take, a file or stdin carries no commands",
             g->def.source, mr_glove_cmd_name(cmd->type));
    return -1;
  }
  mr_glove_pending *p = slot(g);
  if (p == NULL) {
    snprintf(msg, msg_size, "glove %s: %d commands are already waiting for an answer",
             g->def.source, MR_GLOVE_MAX_PENDING);
    return -1;
  }
  /* The slot is free while its tag is chosen: the tag it held may be
   * taken again, and the tag 0 it would hold is left out by fresh_tag's
   * own rule, not by chance. */
  memset(p, 0, sizeof *p);
  p->result.tag = fresh_tag(g);
  p->used = true;
  p->serial = ++g->cmd_serial;
  p->cmd = *cmd;
  p->result.state = MR_GLOVE_CMD_PENDING;
  p->result.type = cmd->type;
  p->len = encode(cmd, p->result.tag, p->wire);
  p->next_send = now;
  mr_glove_cmd_poll(g, now);
  return p->result.tag;
}

mr_glove_cmd_result mr_glove_command_result(const mr_glove *g, int tag) {
  mr_glove_cmd_result none;
  memset(&none, 0, sizeof none);
  for (int i = 0; g != NULL && i < MR_GLOVE_MAX_PENDING; i++)
    if (g->cmds[i].used && g->cmds[i].result.tag == tag) return g->cmds[i].result;
  return none;
}

const gp_status *mr_glove_status_frame(const mr_glove *g) {
  return g != NULL && g->have_status ? &g->status : NULL;
}

/* A send while the port is closed is a try all the same: a glove that is
 * not there times the command out in cmd_tries × cmd_timeout. */
void mr_glove_cmd_poll(mr_glove *g, double now) {
  for (int i = 0; i < MR_GLOVE_MAX_PENDING; i++) {
    mr_glove_pending *p = &g->cmds[i];
    if (!p->used || p->result.state != MR_GLOVE_CMD_PENDING || now < p->next_send) continue;
    if (p->result.sends >= g->def.cmd_tries) {
      p->result.state = MR_GLOVE_CMD_TIMED_OUT;
      continue;
    }
    p->result.sends++;
    p->next_send = now + g->def.cmd_timeout;
    if (!g->open) continue;
    mr_io_error err;
    /* A loss shows on the read. */
    if (g->net != NULL)
      (void)mr_net_publish(g->net, MR_NET_CMD, p->wire, p->len, &err);
    else
      (void)mr_io_write(&g->io, p->wire, p->len, 100, NULL, &err);
  }
}

static mr_glove_pending *answered(mr_glove *g, uint8_t tag, uint8_t cmd) {
  for (int i = 0; i < MR_GLOVE_MAX_PENDING; i++) {
    mr_glove_pending *p = &g->cmds[i];
    if (p->used && p->result.state == MR_GLOVE_CMD_PENDING && p->result.tag == tag &&
        p->result.type == cmd)
      return p;
  }
  return NULL;
}

void mr_glove_cmd_reply(mr_glove *g, const gp_msg *m) {
  if (m->type == GP_STATUS) {
    g->status = m->u.status;
    g->have_status = true;
    return;
  }
  mr_glove_pending *p = NULL;
  if (m->type == GP_ACK && (p = answered(g, m->u.ack.tag, m->u.ack.cmd)) != NULL) {
    p->result.state = MR_GLOVE_CMD_ACKED;
    if (p->cmd.type == GP_STREAM_OFF) g->stream_off = true;
    if (p->cmd.type == GP_STREAM_ON) g->stream_off = false;
    if (p->cmd.type == GP_SET_RATE && p->cmd.baud != 0) g->follow_baud = p->cmd.baud;
  } else if (m->type == GP_NACK && (p = answered(g, m->u.nack.tag, m->u.nack.cmd)) != NULL) {
    p->result.state = MR_GLOVE_CMD_NACKED;
    p->result.nack_reason = m->u.nack.reason;
  }
}

int mr_glove_send_raw(mr_glove *g, const uint8_t *bytes, size_t len, char *msg, size_t msg_size) {
  char dummy[8];
  if (msg == NULL || msg_size == 0) {
    msg = dummy;
    msg_size = sizeof dummy;
  }
  if (g == NULL || bytes == NULL || len == 0) {
    snprintf(msg, msg_size, "expected a glove and bytes to send");
    return -1;
  }
  if (!g->writable || !g->open) {
    snprintf(msg, msg_size, "glove %s: %s", g->def.source,
             g->writable ? "not open: the bytes are dropped" : "carries no commands");
    return -1;
  }
  mr_io_error err;
  if (g->net != NULL) {
    if (mr_net_publish(g->net, MR_NET_CMD, bytes, len, &err) == 0) return 0;
  } else {
    mr_io_status st = mr_io_write(&g->io, bytes, len, 100, NULL, &err);
    if (st == MR_IO_OK) return 0;
    if (!mr_io_failed(st)) snprintf(err.msg, sizeof err.msg, "%s", mr_io_status_name(st));
  }
  snprintf(msg, msg_size, "glove %s: %s", g->def.source, err.msg);
  return -1;
}
