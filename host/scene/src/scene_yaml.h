/* A YAML document as a small tree whose every node knows its line and
 * column. Built from libfyaml's event stream because the event marks are
 * the positions the parser itself saw: the loader reports every error as
 * file:line:column without a second pass over the text. */
#ifndef MR_SCENE_YAML_H
#define MR_SCENE_YAML_H

#include <stdbool.h>
#include <stddef.h>

typedef enum mr_ynode_kind { MR_YNODE_SCALAR, MR_YNODE_MAP, MR_YNODE_SEQ } mr_ynode_kind;

typedef struct mr_ynode {
  mr_ynode_kind kind;
  int line;   /* 1-based */
  int column; /* 1-based */
  /* Scalars: the value after YAML unescaping, NUL-terminated. */
  const char *text;
  bool quoted;
  /* Sequences: items[0..count). Mappings: key i at items[2i], its value at
   * items[2i+1], count = number of pairs. */
  struct mr_ynode **items;
  size_t count;
} mr_ynode;

typedef struct mr_yarena mr_yarena;

typedef struct mr_ydoc {
  mr_yarena *arena;
  mr_ynode *root; /* NULL for an empty document */
} mr_ydoc;

/* Where and why parsing stopped. */
typedef struct mr_yerror {
  int line;
  int column;
  char message[256];
} mr_yerror;

/* Parses exactly one YAML document from text[0..len). Returns 0 on success,
 * -1 with *err filled on a syntax error, a NUL byte, an unknown alias, a
 * duplicate mapping key, a non-scalar key or a second document. */
int mr_scene_yaml_parse(const char *text, size_t len, mr_ydoc *doc, mr_yerror *err);
void mr_scene_yaml_free(mr_ydoc *doc);

/* The same; read_ahead false leaves every line to libfyaml, so that tests
 * can hold the two ways to one tree. */
int mr_scene_yaml_parse_opt(const char *text, size_t len, bool read_ahead, mr_ydoc *doc,
                            mr_yerror *err);

/* Flow mappings that fill the rest of a "- {...}" line, read ahead of
 * libfyaml (scene_yaml_flow.c): the offsets of their braces. */
typedef struct mr_yspan {
  size_t open;
  size_t close;
} mr_yspan;
/* The spans of text in file order (*spans malloc'd, NULL when none). */
size_t mr_scene_yaml_flow_find(const char *text, size_t len, mr_yspan **spans);
/* A malloc'd copy of text with each span's inside blanked, or NULL. */
char *mr_scene_yaml_flow_blank(const char *text, size_t len, const mr_yspan *spans, size_t n);
typedef enum mr_yflow_token {
  MR_YFLOW_END,
  MR_YFLOW_SCALAR,
  MR_YFLOW_SEQ_START,
  MR_YFLOW_SEQ_END
} mr_yflow_token;
/* The next token of a span's inside from *pos, which it moves on; a
 * scalar is text[*at, *at + *len). */
mr_yflow_token mr_scene_yaml_flow_next(const char *text, size_t *pos, size_t close, size_t *at,
                                       size_t *len);

/* The value of key in a mapping, or NULL. */
const mr_ynode *mr_scene_yaml_get(const mr_ynode *map, const char *key);
const char *mr_scene_yaml_kind_name(mr_ynode_kind kind);

#endif
