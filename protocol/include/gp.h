/* The glove protocol codec: framing, CRC, packing and a streaming decoder.
 *
 * Freestanding C11: no allocation, no stdio, bounded buffers. The firmware
 * and the host build the same sources. The wire format is in SPEC.md:
 *
 *   raw frame  = type (1) | payload (GP_<TYPE>_LEN) | CRC-32C (4, little-endian)
 *   wire frame = COBS(raw frame) | 0x00
 *
 * The CRC covers the spec hash (4 bytes, little-endian) followed by type and
 * payload, except for INFO, whose CRC covers type and payload only, so that a
 * host can read the spec hash of a device built from another definition.
 */
#ifndef GP_H
#define GP_H

#include <stddef.h>
#include <stdint.h>

#include "gp_messages.h"

#define GP_CRC_LEN 4u
/* Largest raw frame (type + payload + CRC) and largest wire frame (COBS adds
 * one byte per 254 plus one; then the delimiter). */
#define GP_MAX_FRAME (1u + GP_MAX_PAYLOAD + GP_CRC_LEN)
#define GP_MAX_WIRE  (GP_MAX_FRAME + GP_MAX_FRAME / 254u + 1u + 1u)

/* --- CRC-32C (catalogue name CRC-32/ISCSI, check value 0xE3069283) ------- */

/* Incremental form: start with crc = 0, feed pieces, the result is the
 * catalogue CRC of their concatenation. */
uint32_t gp_crc32c(uint32_t crc, const void *data, size_t len);

/* --- COBS ----------------------------------------------------------------- */

/* Encodes len bytes into out (no delimiter added). Returns the encoded length,
 * or 0 if cap is too small. */
size_t gp_cobs_encode(const uint8_t *in, size_t len, uint8_t *out, size_t cap);
/* Decodes a delimiter-free COBS block. Returns the decoded length, or -1 if
 * the block is malformed (contains 0x00, or a code runs past the end) or the
 * result does not fit cap. */
int gp_cobs_decode(const uint8_t *in, size_t len, uint8_t *out, size_t cap);

/* --- messages ------------------------------------------------------------- */

/* The layout of a type, or NULL for a type this spec does not define. */
const gp_msg_desc *gp_msg_find(uint8_t type);

/* Packs m into type | payload | CRC. Returns the raw frame length, or 0 if
 * the type is unknown or cap is too small. Field values wider than their
 * declared width are truncated to it. */
size_t gp_frame_pack(const gp_msg *m, uint32_t spec_hash, uint8_t *raw, size_t cap);

/* Packs and frames m: COBS-encoded raw frame followed by the 0x00 delimiter.
 * Returns the wire length (at most GP_MAX_WIRE), or 0 on error as above. */
size_t gp_encode(const gp_msg *m, uint32_t spec_hash, uint8_t *wire, size_t cap);

/* Unpacks a payload of a known type into m (no CRC involved). Returns 0, or
 * -1 if the type is unknown or len is not the type's payload length. */
int gp_payload_unpack(uint8_t type, const uint8_t *payload, size_t len, gp_msg *m);

/* The CRC a raw frame's last four bytes must hold: CRC-32C over the spec hash
 * (little-endian) then type and payload; over type and payload alone for the
 * unseeded type (INFO). */
uint32_t gp_frame_crc(uint32_t spec_hash, const uint8_t *raw, size_t len_without_crc);

/* --- streaming decoder ---------------------------------------------------- */

/* What one call to gp_decoder_feed ended on. Every byte of a stream belongs to
 * exactly one event; SPEC.md, "Receiver rules", says what each means. */
typedef enum gp_event {
  GP_EV_NONE = 0,      /* input consumed, no frame ended */
  GP_EV_FRAME,         /* a valid frame: *out is filled */
  GP_EV_FRAME_LATE,    /* a valid SAMPLE that arrived after a newer one: *out filled */
  GP_EV_DUPLICATE,     /* a SAMPLE whose sequence number was already seen: *out filled */
  GP_EV_CRC_ERROR,     /* right length, CRC fails under the host's and any announced hash */
  GP_EV_FRAMING_ERROR, /* malformed COBS, too short, or wrong length for its type */
  GP_EV_OVERSIZE,      /* more than GP_MAX_WIRE bytes without a delimiter */
  GP_EV_UNKNOWN_TYPE,  /* CRC good, type not in this spec */
  GP_EV_SPEC_MISMATCH, /* a frame from a device built from another spec (INFO: *out filled) */
} gp_event;

/* SPEC.md, "Receiver rules", names each counter and which frames count where.
 * Empty frames, and a receiver's tail before its first 0x00, count only in
 * bytes. */
typedef struct gp_counters {
  uint32_t frames; /* delivered: GP_EV_FRAME + GP_EV_FRAME_LATE (restarts included) */
  uint32_t crc_errors;
  uint32_t framing_errors;
  uint32_t oversize;
  uint32_t unknown_type;
  uint32_t spec_mismatch;
  uint32_t lost;         /* SAMPLE sequence numbers skipped and never seen */
  uint32_t duplicates;   /* SAMPLEs already seen; not in frames */
  uint32_t reordered;    /* late SAMPLEs (each was first counted as lost, then taken back) */
  uint32_t seq_restarts; /* SAMPLEs that start a new sequence (START, or a jump too far back) */
  uint64_t bytes;        /* every byte fed */
} gp_counters;

/* How far back the decoder remembers sequence numbers to tell a late frame
 * from a duplicate. */
#define GP_SEQ_WINDOW 64u

/* A run longer than GP_MAX_WIRE that may still be a frame from another
 * definition (SPEC.md, "Receiver rules" 2): decoded as it arrives, keeping
 * only what rules 4 and 5 need, so memory stays bounded at any length. */
typedef struct gp_long_frame {
  uint8_t active;
  uint8_t left;          /* data bytes left in the current COBS group */
  uint8_t zero_due;      /* a zero goes before the next group */
  uint8_t head[6];       /* type, proto_major, spec_hash */
  uint8_t tail[4];       /* the newest four raw bytes, by raw index mod 4 */
  uint64_t n;            /* raw bytes so far */
  uint32_t crc_unseeded; /* CRC-32C of the raw bytes before the newest four */
  uint32_t crc_peer;     /* the same, seeded with the peer's hash */
} gp_long_frame;

typedef struct gp_decoder {
  uint32_t spec_hash; /* the host's */
  uint32_t peer_hash; /* the hash a foreign INFO announced */
  uint8_t peer_known;
  uint8_t have_seq;
  uint8_t overflow;       /* discarding until the next delimiter */
  uint8_t in_step;        /* a 0x00 has been seen: frames start where they should */
  uint8_t seq_high_start; /* the frame at seq_high carried GP_SAMPLE_F_START */
  uint8_t new_link;       /* no SAMPLE since gp_decoder_new_link */
  uint16_t seq_high;      /* highest SAMPLE sequence number seen */
  uint32_t seq_high_t_us; /* and its device time */
  uint64_t seq_seen;      /* bit i: seq_high - i was seen */
  size_t len;
  uint8_t buf[GP_MAX_WIRE];
  /* GP_MAX_WIRE bytes without a delimiter decode to at most one byte more
   * than GP_MAX_FRAME: room for a frame from another definition. */
  uint8_t raw[GP_MAX_WIRE - 1u];
  gp_long_frame lf;
  gp_counters c;
} gp_decoder;

void gp_decoder_init(gp_decoder *d, uint32_t spec_hash);

/* The bytes that follow come over a new link (the receiver reopened the
 * port or took a new connection): none of them repeats a frame from
 * before, so the next SAMPLE, if it is not ahead of the highest sequence
 * number seen, starts a new sequence (SPEC.md, section 9) instead of
 * being taken for a duplicate or a late frame. The counters go on. */
void gp_decoder_new_link(gp_decoder *d);

/* Consumes bytes from data until one frame ends (or all n are consumed).
 * Returns how many bytes it consumed and stores what the frame was in *ev;
 * *out is written only for the events that say so. Call again with the rest.
 * Never reads past data + n, never fails, never allocates. */
size_t gp_decoder_feed(gp_decoder *d, const uint8_t *data, size_t n, gp_msg *out, gp_event *ev);

/* The one-line name of an event, for logs ("crc error", ...). */
const char *gp_event_name(gp_event ev);

#endif
