/* Packing messages to bytes and back, driven by the generated layout tables:
 * fields are packed back to back, least significant bit first, so a field's
 * bit k lands in payload bit (offset + k). One generic walk serves every
 * message, which keeps the firmware small and the two ends identical. */
#include "gp.h"

const gp_msg_desc *gp_msg_find(uint8_t type) {
  for (size_t i = 0; i < gp_msg_desc_count; i++)
    if (gp_msg_descs[i].type == type) return &gp_msg_descs[i];
  return NULL;
}

static uint32_t load_elem(const uint8_t *p, uint8_t size) {
  switch (size) {
  case 1:
    return *p;
  case 2:
    return *(const uint16_t *)(const void *)p;
  default:
    return *(const uint32_t *)(const void *)p;
  }
}

static void store_elem(uint8_t *p, uint8_t size, uint32_t v) {
  switch (size) {
  case 1:
    *p = (uint8_t)v;
    break;
  case 2:
    *(uint16_t *)(void *)p = (uint16_t)v;
    break;
  default:
    *(uint32_t *)(void *)p = v;
    break;
  }
}

/* Both walks move up to one byte per iteration: a field spans at most five
 * bytes, so a field costs at most five steps whatever its alignment. */
static void put_bits(uint8_t *buf, unsigned bit, unsigned width, uint32_t v) {
  while (width) {
    unsigned shift = bit & 7u, take = 8u - shift;
    if (take > width) take = width;
    uint8_t mask = (uint8_t)(((1u << take) - 1u) << shift);
    uint8_t *b = &buf[bit >> 3];
    *b = (uint8_t)((*b & ~mask) | ((v << shift) & mask));
    v >>= take;
    bit += take;
    width -= take;
  }
}

static uint32_t get_bits(const uint8_t *buf, unsigned bit, unsigned width) {
  uint32_t v = 0;
  unsigned got = 0;
  while (got < width) {
    unsigned shift = bit & 7u, take = 8u - shift;
    if (take > width - got) take = width - got;
    uint32_t part = (uint32_t)(buf[bit >> 3] >> shift) & ((1u << take) - 1u);
    v |= part << got;
    bit += take;
    got += take;
  }
  return v;
}

uint32_t gp_frame_crc(uint32_t spec_hash, const uint8_t *raw, size_t len_without_crc) {
  uint32_t crc = 0;
  if (len_without_crc == 0 || raw[0] != GP_UNSEEDED_TYPE) {
    const uint8_t seed[4] = { (uint8_t)spec_hash, (uint8_t)(spec_hash >> 8),
                              (uint8_t)(spec_hash >> 16), (uint8_t)(spec_hash >> 24) };
    crc = gp_crc32c(crc, seed, sizeof seed);
  }
  return gp_crc32c(crc, raw, len_without_crc);
}

size_t gp_frame_pack(const gp_msg *m, uint32_t spec_hash, uint8_t *raw, size_t cap) {
  const gp_msg_desc *d = gp_msg_find(m->type);
  if (!d || cap < 1u + d->len + GP_CRC_LEN) return 0;
  const uint8_t *base = (const uint8_t *)&m->u;
  uint8_t *payload = raw + 1;
  raw[0] = m->type;
  for (unsigned i = 0; i < d->len; i++) payload[i] = 0;
  for (unsigned f = 0; f < d->n_fields; f++) {
    const gp_field_desc *fd = &d->fields[f];
    for (unsigned e = 0; e < fd->count; e++) {
      uint32_t v = load_elem(base + fd->offset + e * fd->elem_size, fd->elem_size);
      put_bits(payload, fd->bit_offset + e * fd->bits, fd->bits, v);
    }
  }
  size_t n = 1u + d->len;
  uint32_t crc = gp_frame_crc(spec_hash, raw, n);
  for (unsigned k = 0; k < 4; k++) raw[n + k] = (uint8_t)(crc >> (8 * k));
  return n + GP_CRC_LEN;
}

size_t gp_encode(const gp_msg *m, uint32_t spec_hash, uint8_t *wire, size_t cap) {
  uint8_t raw[GP_MAX_FRAME];
  size_t n = gp_frame_pack(m, spec_hash, raw, sizeof raw);
  if (n == 0 || cap < 2) return 0;
  size_t w = gp_cobs_encode(raw, n, wire, cap - 1);
  if (w == 0) return 0;
  wire[w] = 0;
  return w + 1;
}

int gp_payload_unpack(uint8_t type, const uint8_t *payload, size_t len, gp_msg *m) {
  const gp_msg_desc *d = gp_msg_find(type);
  if (!d || len != d->len) return -1;
  uint8_t *base = (uint8_t *)&m->u;
  m->type = type;
  for (unsigned f = 0; f < d->n_fields; f++) {
    const gp_field_desc *fd = &d->fields[f];
    for (unsigned e = 0; e < fd->count; e++)
      store_elem(base + fd->offset + e * fd->elem_size, fd->elem_size,
                 get_bits(payload, fd->bit_offset + e * fd->bits, fd->bits));
  }
  return 0;
}
