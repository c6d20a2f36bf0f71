/* Pin-map checker for board_pins.h against hardware/pinout.csv. */
#include "hwpin.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Pins the glove must leave alone: the USB DFU bootloader needs PA11/PA12,
 * and a debug probe needs SWD on PA13/PA14. */
static const struct {
  int port, num;
  const char *what;
} reserved[] = {
  { 0, 11, "USB D- (OTG_FS_DM, DFU bootloader)" },
  { 0, 12, "USB D+ (OTG_FS_DP, DFU bootloader)" },
  { 0, 13, "SWDIO (debug probe)" },
  { 0, 14, "SWCLK (debug probe)" },
};

void hwpin_format(int port, int num, char *buf, size_t len) {
  snprintf(buf, len, "P%c%d", 'A' + port, num);
}

int hwpin_adc1_input(int port, int num) {
  /* STM32F411 datasheet, pin definitions: ADC1_IN0..7 on PA0..7,
   * IN8/IN9 on PB0/PB1, IN10..15 on PC0..5. */
  if (port == 0 && num <= 7) return num;
  if (port == 1 && num <= 1) return 8 + num;
  if (port == 2 && num <= 5) return 10 + num;
  return -1;
}

static void set_err(char *err, size_t len, const char *fmt, ...) {
  va_list ap;
  if (len == 0) return;
  va_start(ap, fmt);
  vsnprintf(err, len, fmt, ap);
  va_end(ap);
}

/* ---- board_pins.h ------------------------------------------------------ */

/* A copy of text with every comment blanked to spaces, newlines kept, so
 * that line and column numbers still point into the original. */
static char *strip_comments(const char *text) {
  size_t n = strlen(text);
  char *s = malloc(n + 1);
  if (!s) return NULL;
  memcpy(s, text, n + 1);
  for (size_t i = 0; i < n; i++) {
    if (s[i] == '/' && i + 1 < n && s[i + 1] == '*') {
      size_t j = i;
      while (j < n && !(s[j] == '*' && j + 1 < n && s[j + 1] == '/')) {
        if (s[j] != '\n') s[j] = ' ';
        j++;
      }
      if (j < n) s[j] = s[j + 1] = ' ';
      i = j + 1;
    } else if (s[i] == '/' && i + 1 < n && s[i + 1] == '/') {
      while (i < n && s[i] != '\n') s[i++] = ' ';
    }
  }
  return s;
}

static const char *skip_blank(const char *p) {
  while (*p == ' ' || *p == '\t') p++;
  return p;
}

static int is_ident(int c) {
  return isalnum(c) || c == '_';
}

/* Parses "BOARD_PIN('A', 1)" at p; returns the end or NULL. */
static const char *parse_board_pin(const char *p, int *port, int *num) {
  static const char kw[] = "BOARD_PIN";
  if (strncmp(p, kw, sizeof kw - 1) != 0) return NULL;
  p = skip_blank(p + sizeof kw - 1);
  if (*p++ != '(') return NULL;
  p = skip_blank(p);
  if (p[0] != '\'' || p[1] < 'A' || p[1] > 'H' || p[2] != '\'') return NULL;
  *port = p[1] - 'A';
  p = skip_blank(p + 3);
  if (*p++ != ',') return NULL;
  p = skip_blank(p);
  if (!isdigit((unsigned char)*p)) return NULL;
  char *end;
  long v = strtol(p, &end, 10);
  if (v < 0 || v > 15) return NULL;
  *num = (int)v;
  p = skip_blank(end);
  if (*p++ != ')') return NULL;
  return p;
}

int hwpin_parse_header(const char *text, const char *path, hwpin_map *out, char *err,
                       size_t err_len) {
  memset(out, 0, sizeof *out);
  out->path = path;
  char *s = strip_comments(text);
  if (!s) {
    set_err(err, err_len, "%s: out of memory", path);
    return -1;
  }
  int rc = 0, line = 1;
  for (char *ln = s; ln && *ln; line++) {
    char *nl = strchr(ln, '\n');
    if (nl) *nl = '\0';
    const char *p = skip_blank(ln);
    if (strncmp(p, "#define", 7) == 0 && (p[7] == ' ' || p[7] == '\t')) {
      p = skip_blank(p + 7);
      const char *name = p;
      while (is_ident((unsigned char)*p)) p++;
      size_t name_len = (size_t)(p - name);
      int is_pin = strncmp(name, "PIN_", 4) == 0;
      int is_adc = strncmp(name, "ADC_CH_", 7) == 0;
      /* function-like macros (BOARD_PIN(port, n), ...) are not signals */
      if (*p != '(' && (is_pin || is_adc)) {
        if (name_len >= HWPIN_NAME_MAX) {
          set_err(err, err_len, "%s:%d:%d: name longer than %d characters", path, line,
                  (int)(name - ln) + 1, HWPIN_NAME_MAX - 1);
          rc = -1;
          break;
        }
        const char *val = skip_blank(p);
        int col = (int)(val - ln) + 1;
        if (is_pin) {
          int port = 0, num = 0;
          const char *end = parse_board_pin(val, &port, &num);
          if (!end || *skip_blank(end) != '\0') {
            set_err(err, err_len, "%s:%d:%d: %.*s: expected BOARD_PIN('<A..H>', <0..15>)", path,
                    line, col, (int)name_len, name);
            rc = -1;
            break;
          }
          if (out->n_pins == HWPIN_MAX) {
            set_err(err, err_len, "%s:%d: more than %d pins", path, line, HWPIN_MAX);
            rc = -1;
            break;
          }
          hwpin_pin *pin = &out->pins[out->n_pins++];
          memcpy(pin->name, name, name_len);
          pin->port = port;
          pin->num = num;
          pin->line = line;
        } else {
          char *end;
          long v = strtol(val, &end, 10);
          if (!isdigit((unsigned char)*val) || *skip_blank(end) != '\0' || v < 0 || v > 18) {
            set_err(err, err_len, "%s:%d:%d: %.*s: expected an ADC channel number 0..18", path,
                    line, col, (int)name_len, name);
            rc = -1;
            break;
          }
          if (out->n_adcs == HWPIN_MAX) {
            set_err(err, err_len, "%s:%d: more than %d ADC channels", path, line, HWPIN_MAX);
            rc = -1;
            break;
          }
          hwpin_adc *adc = &out->adcs[out->n_adcs++];
          memcpy(adc->name, name, name_len);
          adc->channel = (int)v;
          adc->line = line;
        }
      }
    }
    ln = nl ? nl + 1 : NULL;
  }
  free(s);
  return rc;
}

/* ---- pinout.csv -------------------------------------------------------- */

#define CSV_MAX_FIELDS 16
#define CSV_FIELD_MAX  256

typedef struct {
  char text[CSV_FIELD_MAX];
  int col; /* 1-based column of the field's first character */
} csv_field;

/* Splits one record (RFC 4180 quoting, no embedded newlines) starting at
 * *pp; advances *pp past the line end. Returns the field count or -1. */
static int csv_record(const char **pp, const char *line_start, csv_field *f, int max,
                      int *bad_col) {
  const char *p = *pp;
  int n = 0;
  for (;;) {
    if (n == max) {
      *bad_col = (int)(p - line_start) + 1;
      return -1;
    }
    csv_field *cur = &f[n++];
    size_t len = 0;
    cur->col = (int)(p - line_start) + 1;
    if (*p == '"') {
      p++;
      for (;;) {
        if (*p == '\0' || *p == '\n' || *p == '\r') {
          *bad_col = (int)(p - line_start) + 1; /* unterminated quote */
          return -1;
        }
        if (*p == '"') {
          if (p[1] == '"') {
            p++;
          } else {
            p++;
            break;
          }
        }
        if (len + 1 >= CSV_FIELD_MAX) {
          *bad_col = (int)(p - line_start) + 1;
          return -1;
        }
        cur->text[len++] = *p++;
      }
      if (*p != ',' && *p != '\n' && *p != '\r' && *p != '\0') {
        *bad_col = (int)(p - line_start) + 1;
        return -1;
      }
    } else {
      while (*p != ',' && *p != '\n' && *p != '\r' && *p != '\0') {
        if (len + 1 >= CSV_FIELD_MAX) {
          *bad_col = (int)(p - line_start) + 1;
          return -1;
        }
        cur->text[len++] = *p++;
      }
    }
    cur->text[len] = '\0';
    if (*p == ',') {
      p++;
      continue;
    }
    if (*p == '\r') p++;
    if (*p == '\n') p++;
    *pp = p;
    return n;
  }
}

static int find_column(const csv_field *hdr, int n, const char *name) {
  for (int i = 0; i < n; i++)
    if (strcmp(hdr[i].text, name) == 0) return i;
  return -1;
}

/* "PA1" -> port 0, pin 1. */
static int parse_pin_name(const char *s, int *port, int *num) {
  if (s[0] != 'P' || s[1] < 'A' || s[1] > 'H' || !isdigit((unsigned char)s[2])) return -1;
  char *end;
  long v = strtol(s + 2, &end, 10);
  if (*end != '\0' || v > 15 || (s[2] == '0' && s[3] != '\0')) return -1;
  *port = s[1] - 'A';
  *num = (int)v;
  return 0;
}

int hwpin_parse_csv(const char *text, const char *path, hwpin_map *out, char *err, size_t err_len) {
  static const char *const required[] = { "signal", "pin", "adc_signal", "adc_channel" };
  memset(out, 0, sizeof *out);
  out->path = path;
  csv_field *hdr = calloc(CSV_MAX_FIELDS, sizeof *hdr);
  csv_field *f = calloc(CSV_MAX_FIELDS, sizeof *f);
  int rc = -1;
  if (!hdr || !f) {
    set_err(err, err_len, "%s: out of memory", path);
    goto done;
  }
  const char *p = text;
  int line = 1, bad_col = 0;
  int n_hdr = csv_record(&p, text, hdr, CSV_MAX_FIELDS, &bad_col);
  if (n_hdr < 0) {
    set_err(err, err_len, "%s:1:%d: malformed header row", path, bad_col);
    goto done;
  }
  int col[4];
  for (int i = 0; i < 4; i++) {
    col[i] = find_column(hdr, n_hdr, required[i]);
    if (col[i] < 0) {
      set_err(err, err_len, "%s:1:1: header row lacks the column '%s'", path, required[i]);
      goto done;
    }
  }
  while (*p) {
    line++;
    const char *start = p;
    if (*p == '\n' || (*p == '\r' && p[1] == '\n')) { /* blank line */
      p += (*p == '\r') ? 2 : 1;
      continue;
    }
    int n = csv_record(&p, start, f, CSV_MAX_FIELDS, &bad_col);
    if (n < 0) {
      set_err(err, err_len, "%s:%d:%d: malformed field", path, line, bad_col);
      goto done;
    }
    if (n != n_hdr) {
      set_err(err, err_len, "%s:%d:1: %d fields, the header has %d", path, line, n, n_hdr);
      goto done;
    }
    const csv_field *sig = &f[col[0]], *pin = &f[col[1]];
    const csv_field *asig = &f[col[2]], *ach = &f[col[3]];
    if (strncmp(sig->text, "PIN_", 4) != 0 || strlen(sig->text) >= HWPIN_NAME_MAX) {
      set_err(err, err_len, "%s:%d:%d: expected a PIN_* signal name, got '%s'", path, line,
              sig->col, sig->text);
      goto done;
    }
    int port, num;
    if (parse_pin_name(pin->text, &port, &num) != 0) {
      set_err(err, err_len,
              "%s:%d:%d: %s: expected a pin like PA1 (P, port A..H, 0..15), "
              "got '%s'",
              path, line, pin->col, sig->text, pin->text);
      goto done;
    }
    if (out->n_pins == HWPIN_MAX) {
      set_err(err, err_len, "%s:%d: more than %d pins", path, line, HWPIN_MAX);
      goto done;
    }
    hwpin_pin *pp = &out->pins[out->n_pins++];
    strcpy(pp->name, sig->text);
    pp->port = port;
    pp->num = num;
    pp->line = line;
    if ((asig->text[0] == '\0') != (ach->text[0] == '\0')) {
      set_err(err, err_len,
              "%s:%d:%d: %s: adc_signal and adc_channel must both be given or "
              "both be empty",
              path, line, asig->col, sig->text);
      goto done;
    }
    if (asig->text[0] != '\0') {
      char *end;
      long v = strtol(ach->text, &end, 10);
      if (strncmp(asig->text, "ADC_CH_", 7) != 0 || strlen(asig->text) >= HWPIN_NAME_MAX) {
        set_err(err, err_len, "%s:%d:%d: expected an ADC_CH_* name, got '%s'", path, line,
                asig->col, asig->text);
        goto done;
      }
      if (!isdigit((unsigned char)ach->text[0]) || *end != '\0' || v > 18) {
        set_err(err, err_len, "%s:%d:%d: %s: expected an ADC channel number 0..18, got '%s'", path,
                line, ach->col, asig->text, ach->text);
        goto done;
      }
      hwpin_adc *a = &out->adcs[out->n_adcs++];
      strcpy(a->name, asig->text);
      a->channel = (int)v;
      a->line = line;
    }
  }
  rc = 0;
done:
  free(hdr);
  free(f);
  return rc;
}

/* ---- comparison -------------------------------------------------------- */

typedef struct {
  char *buf;
  size_t len, used;
  int count;
} report;

static void problem(report *r, const char *fmt, ...) {
  r->count++;
  if (r->len == 0 || r->used >= r->len - 1) return;
  va_list ap;
  va_start(ap, fmt);
  int n = vsnprintf(r->buf + r->used, r->len - r->used, fmt, ap);
  va_end(ap);
  if (n < 0) return;
  r->used += (size_t)n;
  if (r->used >= r->len - 1) {
    r->used = r->len - 1;
    return;
  }
  r->buf[r->used++] = '\n';
  r->buf[r->used] = '\0';
}

static const hwpin_pin *find_pin(const hwpin_map *m, const char *name) {
  for (int i = 0; i < m->n_pins; i++)
    if (strcmp(m->pins[i].name, name) == 0) return &m->pins[i];
  return NULL;
}

static const hwpin_adc *find_adc(const hwpin_map *m, const char *name) {
  for (int i = 0; i < m->n_adcs; i++)
    if (strcmp(m->adcs[i].name, name) == 0) return &m->adcs[i];
  return NULL;
}

/* Checks one map on its own: no pin twice, none reserved, and every
 * sensor channel's ADC number is the input its pin really carries. */
static void check_alone(const hwpin_map *m, report *r) {
  char a[8];
  for (int i = 0; i < m->n_pins; i++) {
    const hwpin_pin *p = &m->pins[i];
    hwpin_format(p->port, p->num, a, sizeof a);
    for (int j = i + 1; j < m->n_pins; j++) {
      const hwpin_pin *q = &m->pins[j];
      if (q->port == p->port && q->num == p->num)
        problem(r, "%s: %s used twice: %s (line %d) and %s (line %d)", m->path, a, p->name, p->line,
                q->name, q->line);
      if (strcmp(q->name, p->name) == 0)
        problem(r, "%s: %s defined twice (lines %d and %d)", m->path, p->name, p->line, q->line);
    }
    for (size_t k = 0; k < sizeof reserved / sizeof reserved[0]; k++)
      if (reserved[k].port == p->port && reserved[k].num == p->num)
        problem(r, "%s:%d: %s on %s collides with %s", m->path, p->line, p->name, a,
                reserved[k].what);
    if (strncmp(p->name, "PIN_CH_", 7) == 0) {
      char adc_name[HWPIN_NAME_MAX + 8];
      snprintf(adc_name, sizeof adc_name, "ADC_CH_%s", p->name + 7);
      const hwpin_adc *adc = find_adc(m, adc_name);
      int input = hwpin_adc1_input(p->port, p->num);
      if (!adc)
        problem(r, "%s:%d: %s has no %s", m->path, p->line, p->name, adc_name);
      else if (input < 0)
        problem(r, "%s:%d: %s is on %s, which has no ADC1 input", m->path, p->line, p->name, a);
      else if (input != adc->channel)
        problem(r, "%s:%d: %s is on %s, which is ADC1_IN%d, but %s is %d", m->path, adc->line,
                p->name, a, input, adc_name, adc->channel);
    }
  }
  for (int i = 0; i < m->n_adcs; i++)
    for (int j = i + 1; j < m->n_adcs; j++) {
      if (m->adcs[i].channel == m->adcs[j].channel)
        problem(r, "%s: ADC channel %d used twice: %s (line %d) and %s (line %d)", m->path,
                m->adcs[i].channel, m->adcs[i].name, m->adcs[i].line, m->adcs[j].name,
                m->adcs[j].line);
      if (strcmp(m->adcs[i].name, m->adcs[j].name) == 0)
        problem(r, "%s: %s defined twice (lines %d and %d)", m->path, m->adcs[i].name,
                m->adcs[i].line, m->adcs[j].line);
    }
}

int hwpin_compare(const hwpin_map *h, const hwpin_map *c, char *buf, size_t len) {
  report r = { buf, len, 0, 0 };
  if (len) buf[0] = '\0';
  char a[8], b[8];
  for (int i = 0; i < h->n_pins; i++) {
    const hwpin_pin *hp = &h->pins[i];
    const hwpin_pin *cp = find_pin(c, hp->name);
    hwpin_format(hp->port, hp->num, a, sizeof a);
    if (!cp) {
      problem(&r, "%s: %s:%d says %s, %s does not list it", hp->name, h->path, hp->line, a,
              c->path);
    } else if (cp->port != hp->port || cp->num != hp->num) {
      hwpin_format(cp->port, cp->num, b, sizeof b);
      problem(&r, "%s: %s:%d says %s, %s:%d says %s", hp->name, h->path, hp->line, a, c->path,
              cp->line, b);
    }
  }
  for (int i = 0; i < c->n_pins; i++)
    if (!find_pin(h, c->pins[i].name)) {
      hwpin_format(c->pins[i].port, c->pins[i].num, a, sizeof a);
      problem(&r, "%s: %s:%d says %s, %s does not define it", c->pins[i].name, c->path,
              c->pins[i].line, a, h->path);
    }
  for (int i = 0; i < h->n_adcs; i++) {
    const hwpin_adc *ha = &h->adcs[i];
    const hwpin_adc *ca = find_adc(c, ha->name);
    if (!ca)
      problem(&r, "%s: %s:%d says %d, %s does not list it", ha->name, h->path, ha->line,
              ha->channel, c->path);
    else if (ca->channel != ha->channel)
      problem(&r, "%s: %s:%d says %d, %s:%d says %d", ha->name, h->path, ha->line, ha->channel,
              c->path, ca->line, ca->channel);
  }
  for (int i = 0; i < c->n_adcs; i++)
    if (!find_adc(h, c->adcs[i].name))
      problem(&r, "%s: %s:%d says %d, %s does not define it", c->adcs[i].name, c->path,
              c->adcs[i].line, c->adcs[i].channel, h->path);
  check_alone(h, &r);
  check_alone(c, &r);
  return r.count;
}
