#include <inttypes.h>
#include <string.h>

#include "gd_print.h"

static uint32_t field_value(const void *base, const gp_field_desc *fd, unsigned i) {
  const uint8_t *p = (const uint8_t *)base + fd->offset + (size_t)i * fd->elem_size;
  switch (fd->elem_size) {
  case 1:
    return *p;
  case 2: {
    uint16_t v;
    memcpy(&v, p, 2);
    return v;
  }
  default: {
    uint32_t v;
    memcpy(&v, p, 4);
    return v;
  }
  }
}

void gd_print_msg(FILE *f, const gp_msg *m, const char *suffix) {
  const gp_msg_desc *d = gp_msg_find(m->type);
  if (!d) {
    fprintf(f, "type=0x%02X%s\n", m->type, suffix ? suffix : "");
    return;
  }
  fputs(d->name, f);
  for (unsigned k = 0; k < d->n_fields; k++) {
    const gp_field_desc *fd = &d->fields[k];
    /* Hashes and ids read best in hex, as SPEC.md and the labels print them. */
    int hex = strcmp(fd->name, "spec_hash") == 0 || strcmp(fd->name, "uid") == 0 ||
              strcmp(fd->name, "flags") == 0;
    fprintf(f, " %s=", fd->name);
    for (unsigned i = 0; i < fd->count; i++) {
      uint32_t v = field_value(&m->u, fd, i);
      if (i) fputc(',', f);
      if (hex)
        fprintf(f, fd->bits > 8 ? "0x%08" PRIX32 : "0x%" PRIX32, v);
      else
        fprintf(f, "%" PRIu32, v);
    }
  }
  fprintf(f, "%s\n", suffix ? suffix : "");
}

void gd_print_csv_header(FILE *f) {
  fputs("seq,t_us,ch0,ch1,ch2,ch3,ch4,flags,late\n", f);
}

void gd_print_csv_sample(FILE *f, const gp_sample *s, int late) {
  fprintf(f, "%u,%" PRIu32 ",%u,%u,%u,%u,%u,%u,%d\n", s->seq, s->t_us, s->ch[0], s->ch[1], s->ch[2],
          s->ch[3], s->ch[4], s->flags, late);
}

void gd_print_counters(FILE *f, const gp_counters *c) {
  fprintf(f,
          "frames=%" PRIu32 "\ncrc_errors=%" PRIu32 "\nframing_errors=%" PRIu32
          "\noversize=%" PRIu32 "\nunknown_type=%" PRIu32 "\nspec_mismatch=%" PRIu32
          "\nlost=%" PRIu32 "\nduplicates=%" PRIu32 "\nreordered=%" PRIu32 "\nseq_restarts=%" PRIu32
          "\nbytes=%" PRIu64 "\n",
          c->frames, c->crc_errors, c->framing_errors, c->oversize, c->unknown_type,
          c->spec_mismatch, c->lost, c->duplicates, c->reordered, c->seq_restarts, c->bytes);
}
