/* glove-dump --publish: a local glove relayed to a broker's topic, and the
 * commands from the broker down to it (host/net/README.md). */
#ifndef GD_RELAY_H
#define GD_RELAY_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "mr_glove.h"

typedef struct gd_relay gd_relay;

/* Connects to url: 0, or the exit status (2 for a URL that does not parse,
 * 1 for a broker that is not there or refused) after one line on stderr. */
int gd_relay_open(gd_relay **out, const char *url);

/* Bytes the glove sent, as read: its whole frames go out, the samples and
 * INFO on TOPIC, the answers (ACK, NACK, STATUS) on TOPIC/reply; a frame
 * begun waits for its end. */
void gd_relay_bytes(gd_relay *r, const uint8_t *bytes, size_t len);

/* Commands from TOPIC/cmd down to the glove; one line on stderr for a loss
 * of the broker and its return. 0, or 1 once the broker refused the relay
 * (its ACL: one line says so). */
int gd_relay_poll(gd_relay *r, mr_glove *g);

/* The relay's counters as key=value lines, then closes (NULL allowed). */
void gd_relay_close(gd_relay *r, FILE *report);

#endif
