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

/* The value of key in a mapping, or NULL. */
const mr_ynode *mr_scene_yaml_get(const mr_ynode *map, const char *key);
const char *mr_scene_yaml_kind_name(mr_ynode_kind kind);

#endif
