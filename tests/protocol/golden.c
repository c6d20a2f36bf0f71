#define _POSIX_C_SOURCE 200809L /* strtok_r */
#include "golden.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int set_field(gp_msg *m, const gp_msg_desc *d, const char *name, const char *vals) {
  for (unsigned f = 0; f < d->n_fields; f++) {
    const gp_field_desc *fd = &d->fields[f];
    if (strcmp(fd->name, name) != 0) continue;
    const char *p = vals;
    for (unsigned e = 0; e < fd->count; e++) {
      char *end;
      unsigned long v = strtoul(p, &end, 10);
      if (end == p || (e + 1 < fd->count ? *end != ',' : *end != '\0')) return -1;
      p = end + 1;
      uint8_t *dst = (uint8_t *)&m->u + fd->offset + e * fd->elem_size;
      if (fd->elem_size == 1)
        *dst = (uint8_t)v;
      else if (fd->elem_size == 2) {
        uint16_t x = (uint16_t)v;
        memcpy(dst, &x, 2);
      } else {
        uint32_t x = (uint32_t)v;
        memcpy(dst, &x, 4);
      }
    }
    return 0;
  }
  return -1;
}

int golden_load(const char *path, golden_vec *out, int cap, char *err, size_t errlen) {
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(err, errlen, "%s: cannot open", path);
    return -1;
  }
  char line[2048];
  int n = 0, lineno = 0;
  while (fgets(line, sizeof line, f)) {
    lineno++;
    line[strcspn(line, "\r\n")] = 0;
    if (line[0] == '#' || line[0] == 0) continue;
    if (n == cap) {
      snprintf(err, errlen, "%s:%d: more than %d vectors", path, lineno, cap);
      fclose(f);
      return -1;
    }
    golden_vec *v = &out[n];
    memset(v, 0, sizeof *v);
    char *save = NULL, *tok[4];
    for (int i = 0; i < 4; i++) {
      tok[i] = strtok_r(i ? NULL : line, " ", &save);
      if (!tok[i]) {
        snprintf(err, errlen, "%s:%d: expected NAME TYPE HASH WIRE", path, lineno);
        fclose(f);
        return -1;
      }
    }
    snprintf(v->name, sizeof v->name, "%s", tok[0]);
    const gp_msg_desc *d = NULL;
    for (size_t i = 0; i < gp_msg_desc_count; i++)
      if (strcmp(gp_msg_descs[i].name, tok[1]) == 0) d = &gp_msg_descs[i];
    size_t hexlen = strlen(tok[3]);
    if (!d || hexlen % 2 || hexlen / 2 > sizeof v->wire) {
      snprintf(err, errlen, "%s:%d: unknown type or bad wire hex", path, lineno);
      fclose(f);
      return -1;
    }
    v->hash = (uint32_t)strtoul(tok[2], NULL, 16);
    v->msg.type = d->type;
    v->wire_len = hexlen / 2;
    for (size_t i = 0; i < v->wire_len; i++) {
      unsigned b;
      if (sscanf(tok[3] + 2 * i, "%2x", &b) != 1) {
        snprintf(err, errlen, "%s:%d: bad wire hex", path, lineno);
        fclose(f);
        return -1;
      }
      v->wire[i] = (uint8_t)b;
    }
    char *kv;
    while ((kv = strtok_r(NULL, " ", &save))) {
      char *eq = strchr(kv, '=');
      if (!eq || (*eq = 0, set_field(&v->msg, d, kv, eq + 1) != 0)) {
        snprintf(err, errlen, "%s:%d: bad field '%s'", path, lineno, kv);
        fclose(f);
        return -1;
      }
    }
    n++;
  }
  fclose(f);
  return n;
}
