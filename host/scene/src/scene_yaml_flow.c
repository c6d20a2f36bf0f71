/* Flow mappings that fill the rest of a sequence line, read ahead of
 * libfyaml.
 *
 * libfyaml spends about 1 700 instructions on each event. A scene of
 * 100 000 particles is some 200 000 lines such as
 *   "    - {name: p1, position: [0.01, 0.00, 0], mass: 1}"
 * of 12 events each, and parsing them was most of its load time. Such a
 * line's mapping is found here and checked against a strict subset of
 * YAML's flow syntax: plain scalars of letters, digits and "_.+-", pairs
 * "key: value" whose value is such a scalar or a flat sequence of them,
 * on one line, followed by nothing but blanks or a comment. The parser
 * then reads a copy of the text in which each such mapping is blanked to
 * "{      }", every byte, line and column where it was, and the tree
 * builder fills the mapping from the original (scene_yaml.c). libfyaml
 * still reads every line and all of the structure; a mapping this file
 * does not take stays its alone. */
#include "scene_yaml.h"

#include <stdlib.h>
#include <string.h>

/* Longer scalars are left to libfyaml, which limits implicit keys to
 * 1 024 characters. */
#define MR_YFLOW_MAX_SCALAR 128

static bool is_plain(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '.' || c == '+' || c == '-';
}

/* s[i], or a line break past the line's end. */
static char at(const char *s, size_t i, size_t end) {
  return i < end ? s[i] : '\n';
}

static size_t skip_blanks(const char *s, size_t i, size_t end) {
  while (i < end && s[i] == ' ') i++;
  return i;
}

/* The end of the plain scalar at s[i], or 0 when none of ours is there.
 * A '-' may start one only before a character that cannot make it an
 * indicator ("-0.5", not "- " or "--"). */
static size_t scalar_end(const char *s, size_t i, size_t end) {
  size_t j = i;
  while (j < end && is_plain(s[j])) j++;
  if (j == i || j - i > MR_YFLOW_MAX_SCALAR) return 0;
  if (s[i] == '-' && (j - i == 1 || s[i + 1] == '-' || s[i + 1] == '+')) return 0;
  return j;
}

/* A value: a scalar or "[a, b, ...]" of scalars; its end or 0. */
static size_t value_end(const char *s, size_t i, size_t end) {
  if (at(s, i, end) != '[') return scalar_end(s, i, end);
  i = skip_blanks(s, i + 1, end);
  if (at(s, i, end) == ']') return i + 1;
  for (;;) {
    if ((i = scalar_end(s, i, end)) == 0) return 0;
    i = skip_blanks(s, i, end);
    if (at(s, i, end) == ']') return i + 1;
    if (at(s, i, end) != ',') return 0;
    i = skip_blanks(s, i + 1, end);
  }
}

/* The '}' closing the mapping opened at s[open], when all of it is ours;
 * else 0. */
static size_t mapping_end(const char *s, size_t open, size_t end) {
  size_t i = skip_blanks(s, open + 1, end);
  if (at(s, i, end) == '}') return i;
  for (;;) {
    if ((i = scalar_end(s, i, end)) == 0 || at(s, i, end) != ':' || at(s, i + 1, end) != ' ')
      return 0;
    if ((i = value_end(s, skip_blanks(s, i + 1, end), end)) == 0) return 0;
    i = skip_blanks(s, i, end);
    if (at(s, i, end) == '}') return i;
    if (at(s, i, end) != ',') return 0;
    i = skip_blanks(s, i + 1, end);
  }
}

/* "<blanks>- <blanks>{...}<blanks>[# comment]" on the line s[from, end). */
static bool line_span(const char *s, size_t from, size_t end, mr_yspan *span) {
  size_t i = skip_blanks(s, from, end);
  if (at(s, i, end) != '-' || at(s, i + 1, end) != ' ') return false;
  i = skip_blanks(s, i + 2, end);
  if (at(s, i, end) != '{') return false;
  size_t close = mapping_end(s, i, end);
  if (close == 0) return false;
  size_t j = skip_blanks(s, close + 1, end);
  if (j < end && !(s[j] == '#' && j > close + 1)) return false;
  span->open = i;
  span->close = close;
  return true;
}

size_t mr_scene_yaml_flow_find(const char *text, size_t len, mr_yspan **out) {
  mr_yspan *spans = NULL;
  size_t n = 0, cap = 0;
  for (size_t from = 0; from < len;) {
    const char *nl = memchr(text + from, '\n', len - from);
    size_t end = nl ? (size_t)(nl - text) : len;
    mr_yspan span;
    if (line_span(text, from, end, &span) && span.close > span.open + 1) {
      if (n == cap) {
        size_t c = cap ? 2 * cap : 256;
        mr_yspan *t = realloc(spans, c * sizeof *t);
        if (t == NULL) break; /* the rest is libfyaml's */
        spans = t;
        cap = c;
      }
      spans[n++] = span;
    }
    from = end + 1;
  }
  *out = spans;
  return n;
}

char *mr_scene_yaml_flow_blank(const char *text, size_t len, const mr_yspan *spans, size_t n) {
  char *copy = malloc(len ? len : 1);
  if (copy == NULL) return NULL;
  memcpy(copy, text, len);
  for (size_t k = 0; k < n; k++)
    memset(copy + spans[k].open + 1, ' ', spans[k].close - spans[k].open - 1);
  return copy;
}

mr_yflow_token mr_scene_yaml_flow_next(const char *text, size_t *pos, size_t close, size_t *at_,
                                       size_t *len) {
  size_t i = *pos;
  while (i < close && (text[i] == ' ' || text[i] == ',' || text[i] == ':')) i++;
  *at_ = i;
  *len = 0;
  if (i >= close) {
    *pos = close;
    return MR_YFLOW_END;
  }
  if (text[i] == '[' || text[i] == ']') {
    *pos = i + 1;
    return text[i] == '[' ? MR_YFLOW_SEQ_START : MR_YFLOW_SEQ_END;
  }
  size_t j = i;
  while (j < close && is_plain(text[j])) j++;
  *len = j - i;
  *pos = j;
  return MR_YFLOW_SCALAR;
}
