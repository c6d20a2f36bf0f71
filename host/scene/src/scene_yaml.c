#include "scene_yaml.h"

#include <libfyaml.h>
#include <stdalign.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* All nodes and texts of one document live in one arena, so aliases may
 * share nodes and freeing is one walk over the blocks. */
struct mr_yarena {
  struct mr_yarena *next;
  size_t used;
  size_t cap;
  alignas(max_align_t) unsigned char data[];
};

/* No scene nests deeper than a few levels; a file nested millions deep
 * must not build millions of open containers. */
#define MR_YAML_MAX_DEPTH 64

/* Uninitialised: every caller writes all of it. */
static void *arena_alloc(mr_yarena **head, size_t size) {
  size = (size + alignof(max_align_t) - 1) & ~(alignof(max_align_t) - 1);
  mr_yarena *a = *head;
  if (a == NULL || a->cap - a->used < size) {
    size_t cap = size > 16384 ? size : 16384;
    mr_yarena *b = malloc(sizeof *b + cap);
    if (b == NULL) return NULL;
    b->next = a;
    b->used = 0;
    b->cap = cap;
    *head = b;
    a = b;
  }
  void *p = a->data + a->used;
  a->used += size;
  return p;
}

static void arena_free(mr_yarena *a) {
  while (a != NULL) {
    mr_yarena *next = a->next;
    free(a);
    a = next;
  }
}

/* A container under construction: its children gather on the builder's
 * one stack of children, from `first` on, and move into the arena when
 * the container ends; no allocation per container. */
typedef struct frame {
  mr_ynode *node;
  size_t first;
  size_t n;
  char *anchor; /* registered when the container ends */
} frame;

typedef struct anchor {
  char *name;
  mr_ynode *node;
} anchor;

typedef struct builder {
  mr_ydoc *doc;
  mr_yerror *err;
  frame *stack;
  size_t depth;
  size_t stack_cap;
  mr_ynode **kids; /* the open containers' children, innermost last */
  size_t n_kids;
  size_t kids_cap;
  anchor *anchors;
  size_t n_anchors;
  size_t anchors_cap;
  int documents;
  /* Mappings read ahead (scene_yaml_flow.c): the original text, the spans
   * in file order, the next one libfyaml must open, and the close of the
   * one it opened last, which must come next; (size_t)-1 when none. */
  const char *text;
  const mr_yspan *spans;
  size_t n_spans;
  size_t next_span;
  size_t close_at;
} builder;

static int fail(mr_yerror *err, int line, int column, const char *fmt, ...) {
  err->line = line;
  err->column = column;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err->message, sizeof err->message, fmt, ap);
  va_end(ap);
  return -1;
}

static char *token_dup(mr_yarena **arena, struct fy_token *t) {
  size_t len = 0;
  const char *s = t ? fy_token_get_text(t, &len) : "";
  if (s == NULL) {
    s = "";
    len = 0;
  }
  char *out = arena_alloc(arena, len + 1);
  if (out != NULL) {
    memcpy(out, s, len);
    out[len] = '\0';
  }
  return out;
}

static char *token_strdup(struct fy_token *t) {
  size_t len = 0;
  const char *s = fy_token_get_text(t, &len);
  char *out = malloc(len + 1);
  if (out != NULL) {
    memcpy(out, s ? s : "", len);
    out[len] = '\0';
  }
  return out;
}

static int add_anchor(builder *b, char *name, mr_ynode *node) {
  if (b->n_anchors == b->anchors_cap) {
    size_t cap = b->anchors_cap ? 2 * b->anchors_cap : 8;
    anchor *a = realloc(b->anchors, cap * sizeof *a);
    if (a == NULL) {
      free(name);
      return fail(b->err, node->line, node->column, "out of memory");
    }
    b->anchors = a;
    b->anchors_cap = cap;
  }
  /* A later anchor of the same name shadows the earlier one (YAML 1.2). */
  b->anchors[b->n_anchors].name = name;
  b->anchors[b->n_anchors].node = node;
  b->n_anchors++;
  return 0;
}

static mr_ynode *find_anchor(const builder *b, const char *name) {
  for (size_t i = b->n_anchors; i-- > 0;)
    if (strcmp(b->anchors[i].name, name) == 0) return b->anchors[i].node;
  return NULL;
}

static bool same_scalar(const mr_ynode *a, const mr_ynode *b) {
  return a->kind == MR_YNODE_SCALAR && b->kind == MR_YNODE_SCALAR && strcmp(a->text, b->text) == 0;
}

/* Attach a finished node to the container on top of the stack. */
static int attach(builder *b, mr_ynode *node) {
  if (b->depth == 0) {
    b->doc->root = node;
    return 0;
  }
  frame *f = &b->stack[b->depth - 1];
  if (f->node->kind == MR_YNODE_MAP && f->n % 2 == 0) {
    if (node->kind != MR_YNODE_SCALAR)
      return fail(b->err, node->line, node->column,
                  "expected a plain key, got a %s as a mapping key",
                  mr_scene_yaml_kind_name(node->kind));
    /* Indexed, not b->kids + first: before the first child kids is NULL,
     * and NULL + 0 is undefined (clang's UBSan reports it). */
    for (size_t i = 0; i < f->n; i += 2) {
      const mr_ynode *key = b->kids[f->first + i];
      if (same_scalar(key, node))
        return fail(b->err, node->line, node->column,
                    "duplicate key '%s' (first at line %d, column %d)", node->text, key->line,
                    key->column);
    }
  }
  if (b->n_kids == b->kids_cap) {
    size_t cap = b->kids_cap ? 2 * b->kids_cap : 64;
    mr_ynode **t = realloc(b->kids, cap * sizeof *t);
    if (t == NULL) return fail(b->err, node->line, node->column, "out of memory");
    b->kids = t;
    b->kids_cap = cap;
  }
  b->kids[b->n_kids++] = node;
  f->n++;
  return 0;
}

static mr_ynode *new_node_at(builder *b, mr_ynode_kind kind, int line, int column) {
  mr_ynode *n = arena_alloc(&b->doc->arena, sizeof *n);
  if (n == NULL) {
    fail(b->err, line, column, "out of memory");
    return NULL;
  }
  *n = (mr_ynode){ .kind = kind, .line = line, .column = column, .text = "" };
  return n;
}

static mr_ynode *new_node(builder *b, mr_ynode_kind kind, const struct fy_mark *m) {
  return new_node_at(b, kind, m ? m->line + 1 : 0, m ? m->column + 1 : 0);
}

static int open_container_at(builder *b, mr_ynode_kind kind, int line, int column,
                             struct fy_token *anchor_tok) {
  mr_ynode *n = new_node_at(b, kind, line, column);
  if (n == NULL) return -1;
  if (b->depth >= MR_YAML_MAX_DEPTH)
    return fail(b->err, n->line, n->column, "expected at most %d levels of nesting",
                MR_YAML_MAX_DEPTH);
  if (b->depth == b->stack_cap) {
    size_t cap = b->stack_cap ? 2 * b->stack_cap : 16;
    frame *s = realloc(b->stack, cap * sizeof *s);
    if (s == NULL) return fail(b->err, n->line, n->column, "out of memory");
    b->stack = s;
    b->stack_cap = cap;
  }
  frame *f = &b->stack[b->depth++];
  *f = (frame){ .node = n, .first = b->n_kids };
  if (anchor_tok != NULL) {
    f->anchor = token_strdup(anchor_tok);
    if (f->anchor == NULL) return fail(b->err, n->line, n->column, "out of memory");
  }
  return 0;
}

static int close_container(builder *b) {
  frame *f = &b->stack[b->depth - 1];
  mr_ynode *n = f->node;
  if (f->n > 0) {
    n->items = arena_alloc(&b->doc->arena, f->n * sizeof *n->items);
    if (n->items == NULL) return fail(b->err, n->line, n->column, "out of memory");
    memcpy(n->items, b->kids + f->first, f->n * sizeof *n->items);
  }
  n->count = n->kind == MR_YNODE_MAP ? f->n / 2 : f->n;
  b->n_kids = f->first;
  char *name = f->anchor;
  b->depth--;
  if (name != NULL && add_anchor(b, name, n) != 0) return -1;
  return attach(b, n);
}

/* The inside of a read-ahead mapping that libfyaml has just opened at m,
 * as the events libfyaml would have given for it: its place is libfyaml's
 * for the '{', and the inside is on the same line, in ASCII. */
static int fill_span(builder *b, const mr_yspan *span, const struct fy_mark *m) {
  size_t pos = span->open + 1, at, len;
  mr_yflow_token t;
  while ((t = mr_scene_yaml_flow_next(b->text, &pos, span->close, &at, &len)) != MR_YFLOW_END) {
    int line = m->line + 1, column = m->column + 1 + (int)(at - span->open);
    if (t == MR_YFLOW_SEQ_START) {
      if (open_container_at(b, MR_YNODE_SEQ, line, column, NULL) != 0) return -1;
      continue;
    }
    if (t == MR_YFLOW_SEQ_END) {
      if (close_container(b) != 0) return -1;
      continue;
    }
    mr_ynode *n = new_node_at(b, MR_YNODE_SCALAR, line, column);
    char *text = n ? arena_alloc(&b->doc->arena, len + 1) : NULL;
    if (text == NULL) return fail(b->err, line, column, "out of memory");
    memcpy(text, b->text + at, len);
    text[len] = '\0';
    n->text = text;
    if (attach(b, n) != 0) return -1;
  }
  return 0;
}

/* Read-ahead mappings must open exactly where they were found and close
 * at once; anything else (the '{' was inside a text, say) gives up this
 * parse for one of the original text by libfyaml alone. */
static int follow_spans(builder *b, struct fy_event *e, const struct fy_mark *m) {
  if (b->close_at != (size_t)-1) {
    if (e->type != FYET_MAPPING_END || m == NULL || m->input_pos != b->close_at)
      return fail(b->err, 0, 0, "a mapping read ahead did not close where expected");
    b->close_at = (size_t)-1;
    return 0;
  }
  if (b->next_span == b->n_spans || m == NULL || m->input_pos < b->spans[b->next_span].open)
    return 0;
  const mr_yspan *span = &b->spans[b->next_span++];
  if (e->type != FYET_MAPPING_START || m->input_pos != span->open)
    return fail(b->err, 0, 0, "a mapping read ahead was not opened where expected");
  b->close_at = span->close;
  return fill_span(b, span, m);
}

/* Explicit tags (§3.2.1.1 of YAML 1.2): the core schema's own are
 * honoured, !!str making a scalar text even when it reads as a number;
 * any other is refused rather than silently ignored. *as_text: !!str. */
static int check_tag(builder *b, struct fy_token *tag, int line, int column, bool *as_text) {
  static const char *const core[] = { "str", "int", "float", "bool", "null", "map", "seq" };
  static const char prefix[] = "tag:yaml.org,2002:";
  *as_text = false;
  if (tag == NULL) return 0;
  size_t len = 0;
  const char *t = fy_token_get_text(tag, &len);
  char name[80];
  snprintf(name, sizeof name, "%.*s", (int)(t != NULL && len < 70 ? len : 70), t ? t : "");
  if (strncmp(name, prefix, sizeof prefix - 1) == 0)
    for (size_t i = 0; i < sizeof core / sizeof core[0]; i++)
      if (strcmp(name + sizeof prefix - 1, core[i]) == 0) {
        *as_text = i == 0;
        return 0;
      }
  return fail(b->err, line, column,
              "unsupported tag '%s'; expected no tag, or one of !!str, !!int, !!float, !!bool, "
              "!!null, !!map, !!seq",
              name);
}

/* An empty value has no mark of its own: it is where its key ends, or
 * where its sequence starts. */
static void empty_place(const builder *b, int *line, int *column) {
  *line = *column = 0;
  if (b->depth == 0) return;
  const frame *f = &b->stack[b->depth - 1];
  if (f->node->kind == MR_YNODE_MAP && f->n % 2 == 1) {
    const mr_ynode *key = b->kids[f->first + f->n - 1];
    *line = key->line;
    *column = key->column + (int)strlen(key->text) + (key->quoted ? 2 : 0);
  } else {
    *line = f->node->line;
    *column = f->node->column;
  }
}

static int on_event(builder *b, struct fy_event *e, const struct fy_mark *m) {
  int line = m ? m->line + 1 : 0;
  int column = m ? m->column + 1 : 0;
  switch (e->type) {
  case FYET_DOCUMENT_START:
    if (++b->documents > 1)
      return fail(b->err, line, column, "expected one YAML document, found a second one");
    return 0;
  case FYET_MAPPING_START:
  case FYET_SEQUENCE_START: {
    bool map = e->type == FYET_MAPPING_START, text;
    if (check_tag(b, map ? e->mapping_start.tag : e->sequence_start.tag, line, column, &text) != 0)
      return -1;
    if (text)
      return fail(b->err, line, column, "expected a text for the !!str tag, got a %s",
                  map ? "mapping" : "sequence");
    if (open_container_at(b, map ? MR_YNODE_MAP : MR_YNODE_SEQ, line, column,
                          map ? e->mapping_start.anchor : e->sequence_start.anchor) != 0)
      return -1;
    return b->n_spans > 0 ? follow_spans(b, e, m) : 0;
  }
  case FYET_MAPPING_END:
  case FYET_SEQUENCE_END:
    if (b->n_spans > 0 && follow_spans(b, e, m) != 0) return -1;
    return close_container(b);
  case FYET_SCALAR: {
    mr_ynode *n = new_node(b, MR_YNODE_SCALAR, m);
    if (n == NULL) return -1;
    if (m == NULL) empty_place(b, &n->line, &n->column);
    bool as_text = false;
    if (check_tag(b, e->scalar.tag, n->line, n->column, &as_text) != 0) return -1;
    n->text = token_dup(&b->doc->arena, e->scalar.value);
    if (n->text == NULL) return fail(b->err, line, column, "out of memory");
    enum fy_scalar_style style = fy_token_scalar_style(e->scalar.value);
    n->quoted = style != FYSS_PLAIN || as_text;
    /* libfyaml marks a quoted scalar at its first character inside the
     * quotes; point at the opening quote, where the value starts. */
    if ((style == FYSS_SINGLE_QUOTED || style == FYSS_DOUBLE_QUOTED) && n->column > 1) n->column--;
    if (e->scalar.anchor != NULL) {
      char *name = token_strdup(e->scalar.anchor);
      if (name == NULL || add_anchor(b, name, n) != 0)
        return fail(b->err, line, column, "out of memory");
    }
    return attach(b, n);
  }
  case FYET_ALIAS: {
    size_t len = 0;
    const char *s = fy_token_get_text(e->alias.anchor, &len);
    char name[128];
    snprintf(name, sizeof name, "%.*s", (int)(len < 120 ? len : 120), s ? s : "");
    mr_ynode *target = find_anchor(b, name);
    /* The mark is at the name; the alias starts at its '*'. */
    if (target == NULL)
      return fail(b->err, line, column > 1 ? column - 1 : column,
                  "expected a defined anchor for alias '*%s'", name);
    return attach(b, target);
  }
  default:
    return 0;
  }
}

/* Position of the first NUL byte, if any: such input is not a text file. */
static bool find_nul(const char *text, size_t len, int *line, int *column) {
  const char *z = memchr(text, '\0', len);
  if (z == NULL) return false;
  *line = 1;
  *column = 1;
  for (const char *p = text; p < z; p++) {
    if (*p == '\n') {
      (*line)++;
      *column = 1;
    } else {
      (*column)++;
    }
  }
  return true;
}

/* The first byte that is not part of well-formed UTF-8 (RFC 3629: no
 * overlong forms, no surrogates, nothing past U+10FFFF), or -1. libfyaml
 * (github.com/pantoniou/libfyaml) loops forever on some malformed input,
 * such as a '%' directive line holding a lone 0xC3, so nothing it has not
 * been shown to handle reaches it. */
static long bad_utf8(const unsigned char *s, size_t len) {
  size_t i = 0;
  while (i < len) {
    /* Eight ASCII bytes at a time: nearly every byte of a scene file. */
    uint64_t w;
    if (len - i >= 8 && (memcpy(&w, s + i, 8), (w & 0x8080808080808080u) == 0)) {
      i += 8;
      continue;
    }
    unsigned c = s[i];
    size_t n = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xe ? 2 : (c >> 3) == 0x1e ? 3 : 9;
    if (n == 9 || i + n >= len + (n == 0)) return (long)i;
    unsigned cp = n == 0 ? c : n == 1 ? c & 0x1f : n == 2 ? c & 0x0f : c & 0x07;
    for (size_t k = 1; k <= n; k++) {
      if ((s[i + k] & 0xc0) != 0x80) return (long)i;
      cp = (cp << 6) | (s[i + k] & 0x3f);
    }
    static const unsigned least[4] = { 0, 0x80, 0x800, 0x10000 };
    if (cp < least[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return (long)i;
    i += n + 1;
  }
  return -1;
}

/* libfyaml reads a whole flow collection ahead of its events (a file of
 * three million '[' took a gigabyte before the first event), so flow
 * nesting is measured here first: the offset of the bracket that opens
 * level max_depth + 1, or -1. Quoted scalars and comments are skipped; a
 * plain scalar holding that many brackets is refused too, a price no
 * scene pays. */
static long too_deep(const char *s, size_t len, int max_depth) {
  /* The bytes that matter outside quotes; every other one is skipped by
   * one table look-up. */
  static const bool marks[256] = { ['\''] = true, ['"'] = true, ['#'] = true, ['['] = true,
                                   [']'] = true,  ['{'] = true, ['}'] = true };
  int depth = 0;
  char quote = 0;
  for (size_t i = 0; i < len; i++) {
    if (!quote)
      while (i < len && !marks[(unsigned char)s[i]]) i++;
    if (i == len) break;
    char c = s[i];
    if (quote) {
      if (c == '\\' && quote == '"' && i + 1 < len)
        i++;
      else if (c == quote)
        quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '#' && (i == 0 || s[i - 1] == ' ' || s[i - 1] == '\t' || s[i - 1] == '\n')) {
      while (i + 1 < len && s[i + 1] != '\n') i++;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return (long)i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      depth--;
    }
  }
  return -1;
}

/* Line and column (1-based) of byte offset `at`. */
static void place_of(const char *text, size_t at, int *line, int *column) {
  *line = 1;
  *column = 1;
  for (size_t i = 0; i < at; i++) {
    if (text[i] == '\n') {
      (*line)++;
      *column = 1;
    } else {
      (*column)++;
    }
  }
}

/* A quiet parser over text whose errors gather in *diag, or NULL. */
static struct fy_parser *open_parser(const char *text, size_t len, struct fy_diag **diag) {
  struct fy_diag_cfg dcfg;
  fy_diag_cfg_default(&dcfg);
  dcfg.fp = NULL;
  dcfg.colorize = false;
  *diag = fy_diag_create(&dcfg);
  if (*diag == NULL) return NULL;
  fy_diag_set_collect_errors(*diag, true);
  struct fy_parse_cfg cfg;
  memset(&cfg, 0, sizeof cfg);
  cfg.flags = FYPCF_QUIET | FYPCF_COLLECT_DIAG;
  cfg.diag = *diag;
  struct fy_parser *fyp = fy_parser_create(&cfg);
  if (fyp != NULL && fy_parser_set_string(fyp, text, len) == 0) return fyp;
  if (fyp != NULL) fy_parser_destroy(fyp);
  fy_diag_destroy(*diag);
  return NULL;
}

/* Feeds every event to the builder; on a stream error, names the place
 * libfyaml gives, else the last event's. */
static int build_tree(builder *b, struct fy_parser *fyp, struct fy_diag *diag) {
  int rc = 0;
  int last_line = 1, last_column = 1;
  struct fy_event *e;
  while (rc == 0 && (e = fy_parser_parse(fyp)) != NULL) {
    const struct fy_mark *m = fy_event_start_mark(e);
    if (m != NULL) {
      last_line = m->line + 1;
      last_column = m->column + 1;
    }
    rc = on_event(b, e, m);
    fy_parser_event_free(fyp, e);
  }
  if (rc != 0 || !fy_parser_get_stream_error(fyp)) return rc;
  void *it = NULL;
  struct fy_diag_error *de = fy_diag_errors_iterate(diag, &it);
  if (de != NULL) /* libfyaml's collected diagnostics are already 1-based */
    return fail(b->err, de->line, de->column, "expected valid YAML: %s", de->msg);
  return fail(b->err, last_line, last_column, "expected valid YAML");
}

static void builder_free(builder *b) {
  for (size_t i = 0; i < b->depth; i++) free(b->stack[i].anchor);
  free(b->stack);
  free(b->kids);
  for (size_t i = 0; i < b->n_anchors; i++) free(b->anchors[i].name);
  free(b->anchors);
}

/* Builds the tree of `parsed`, which is `text` with the spans' insides
 * blanked (or text itself, without spans). */
static int parse_text(const char *parsed, const char *text, size_t len, const mr_yspan *spans,
                      size_t n_spans, mr_ydoc *doc, mr_yerror *err) {
  memset(doc, 0, sizeof *doc);
  memset(err, 0, sizeof *err);
  struct fy_diag *diag;
  struct fy_parser *fyp = open_parser(parsed, len, &diag);
  if (fyp == NULL) return fail(err, 0, 0, "out of memory");
  builder b;
  memset(&b, 0, sizeof b);
  b.doc = doc;
  b.err = err;
  b.text = text;
  b.spans = spans;
  b.n_spans = n_spans;
  b.close_at = (size_t)-1;
  int rc = build_tree(&b, fyp, diag);
  if (rc == 0 && (b.next_span != n_spans || b.close_at != (size_t)-1))
    rc = fail(err, 0, 0, "a mapping read ahead was not opened where expected");
  builder_free(&b);
  fy_parser_destroy(fyp);
  fy_diag_destroy(diag);
  if (rc != 0) mr_scene_yaml_free(doc);
  return rc;
}

/* The text with its "- {...}" mappings read ahead (scene_yaml_flow.c);
 * -1 when there are none or the parse fails in any way, so that libfyaml
 * alone reads the original and gives its own errors and places. */
static int parse_ahead(const char *text, size_t len, mr_ydoc *doc, mr_yerror *err) {
  mr_yspan *spans = NULL;
  size_t n = mr_scene_yaml_flow_find(text, len, &spans);
  char *blank = n > 0 ? mr_scene_yaml_flow_blank(text, len, spans, n) : NULL;
  int rc = blank != NULL ? parse_text(blank, text, len, spans, n, doc, err) : -1;
  free(blank);
  free(spans);
  return rc;
}

int mr_scene_yaml_parse_opt(const char *text, size_t len, bool read_ahead, mr_ydoc *doc,
                            mr_yerror *err) {
  memset(doc, 0, sizeof *doc);
  memset(err, 0, sizeof *err);
  int nl, nc;
  if (find_nul(text, len, &nl, &nc))
    return fail(err, nl, nc, "expected a YAML text file, found a NUL byte");
  long bad = bad_utf8((const unsigned char *)text, len);
  if (bad >= 0) {
    place_of(text, (size_t)bad, &nl, &nc);
    return fail(err, nl, nc, "expected UTF-8 text, found the byte 0x%02X",
                (unsigned)(unsigned char)text[bad]);
  }
  bad = too_deep(text, len, MR_YAML_MAX_DEPTH);
  if (bad >= 0) {
    place_of(text, (size_t)bad, &nl, &nc);
    return fail(err, nl, nc, "expected at most %d levels of nesting", MR_YAML_MAX_DEPTH);
  }
  if (read_ahead && parse_ahead(text, len, doc, err) == 0) return 0;
  return parse_text(text, text, len, NULL, 0, doc, err);
}

int mr_scene_yaml_parse(const char *text, size_t len, mr_ydoc *doc, mr_yerror *err) {
  return mr_scene_yaml_parse_opt(text, len, true, doc, err);
}

void mr_scene_yaml_free(mr_ydoc *doc) {
  arena_free(doc->arena);
  doc->arena = NULL;
  doc->root = NULL;
}

const mr_ynode *mr_scene_yaml_get(const mr_ynode *map, const char *key) {
  if (map == NULL || map->kind != MR_YNODE_MAP) return NULL;
  for (size_t i = 0; i < map->count; i++)
    if (map->items[2 * i]->text[0] == key[0] && strcmp(map->items[2 * i]->text, key) == 0)
      return map->items[2 * i + 1];
  return NULL;
}

const char *mr_scene_yaml_kind_name(mr_ynode_kind kind) {
  switch (kind) {
  case MR_YNODE_SCALAR:
    return "scalar";
  case MR_YNODE_MAP:
    return "mapping";
  case MR_YNODE_SEQ:
    return "sequence";
  }
  return "node";
}
