/* The "- {...}" mappings read ahead of libfyaml (scene_yaml_flow.c) give
 * the very tree libfyaml gives alone, node for node with every line and
 * column, and the same error at the same place; where a line only looks
 * like one (inside a block or quoted text, a plain text's next line, a
 * second document), libfyaml's reading stands. */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "scene_yaml.h"

/* Node for node: kind, place, text, quoting, children. */
static void assert_same_tree(const mr_ynode *a, const mr_ynode *b) {
  if (a == NULL || b == NULL) {
    assert_ptr_equal(a, b);
    return;
  }
  assert_int_equal(a->kind, b->kind);
  assert_int_equal(a->line, b->line);
  assert_int_equal(a->column, b->column);
  assert_string_equal(a->text, b->text);
  assert_int_equal(a->quoted, b->quoted);
  assert_int_equal(a->count, b->count);
  size_t n = a->kind == MR_YNODE_MAP ? 2 * a->count : a->kind == MR_YNODE_SEQ ? a->count : 0;
  for (size_t i = 0; i < n; i++) assert_same_tree(a->items[i], b->items[i]);
}

/* Both ways agree on text; returns how many spans were read ahead. */
static size_t assert_same_both_ways(const char *text, size_t len) {
  mr_ydoc ahead, alone;
  mr_yerror e1, e2;
  int r1 = mr_scene_yaml_parse_opt(text, len, true, &ahead, &e1);
  int r2 = mr_scene_yaml_parse_opt(text, len, false, &alone, &e2);
  assert_int_equal(r1, r2);
  if (r1 == 0) {
    assert_same_tree(ahead.root, alone.root);
    mr_scene_yaml_free(&ahead);
    mr_scene_yaml_free(&alone);
  } else {
    assert_int_equal(e1.line, e2.line);
    assert_int_equal(e1.column, e2.column);
    assert_string_equal(e1.message, e2.message);
  }
  mr_yspan *spans;
  size_t n = mr_scene_yaml_flow_find(text, len, &spans);
  free(spans);
  return n;
}

static void a_chain_is_read_ahead_with_libfyaml_places(void **state) {
  (void)state;
  const char *text = "physics:\n"
                     "  particles:\n"
                     "    - {name: p0, position: [0.00, -1.5e-3, +2], mass: 1}  # first\n"
                     "    -   { name: p1 ,  position: [ 1, 2, 3 ], mass: .5 }\n"
                     "    - {name: p2, position: [], mass: 1}\n";
  assert_int_equal(assert_same_both_ways(text, strlen(text)), 3);
  mr_ydoc doc;
  mr_yerror err;
  assert_int_equal(mr_scene_yaml_parse(text, strlen(text), &doc, &err), 0);
  const mr_ynode *list = mr_scene_yaml_get(mr_scene_yaml_get(doc.root, "physics"), "particles");
  assert_int_equal(list->count, 3);
  const mr_ynode *p1 = list->items[1];
  assert_int_equal(p1->line, 4);
  assert_int_equal(p1->column, 9);
  const mr_ynode *pos = mr_scene_yaml_get(p1, "position");
  assert_int_equal(pos->column, 33);
  assert_string_equal(pos->items[2]->text, "3");
  assert_int_equal(pos->items[2]->column, 41);
  assert_string_equal(mr_scene_yaml_get(p1, "mass")->text, ".5");
  mr_scene_yaml_free(&doc);
}

/* Lines that look like "- {...}" but are not mappings, or whose mappings
 * hold more than the read-ahead takes. */
static void lookalikes_and_bad_lines_read_as_libfyaml_reads_them(void **state) {
  (void)state;
  static const char *const texts[] = {
    "a: |\n  - {b: 1}\n",
    "a: >\n  - {b: 1}\n  - {c: [1, 2]}\n",
    "a: \"x\n  - {b: 1}\"\n",
    "a: 'x\n  - {b: 1}'\n",
    "a: some text\n  - {b: 1}\n",
    "- |\n- {b: 1}\n",
    "a:\n  - x\n    - {b: 1}\n",
    "- {a: 1, a: 2}\n",
    "- {a: 1,}\n",
    "- {a: 1, b}\n",
    "- {a: }\n",
    "- {a:1}\n",
    "- {a: 1}#c\n",
    "- {a: 1} x\n",
    "- {a: 1}: 2\n",
    "- {a: [1, 2,]}\n",
    "- {a: {b: 1}}\n",
    "- {a: -}\n",
    "- {a: --1}\n",
    "- {a: 1\t}\n",
    "- {a: 1}\r\n- {b: 2}\r\n",
    "- {a: \xe2\x80\xa8}\n- {b: 2}\n",
    "x: \xe2\x80\xa8\n- {b: 2}\n",
    "%YAML 1.1\n---\n- {a: 1}\n",
    "- {a: 1}\n---\n- {b: 2}\n",
    "- {a: 1}\n...\n",
    "? - {a: 1}\n: x\n",
    "x: [\n  - {a: 1}]\n",
    "- &x {a: 1}\n- *x\n",
    "- !!map {a: 1}\n",
    "- {a: 1}\n  b: 2\n",
    "  - {a: 1}\n - {b: 2}\n",
    "- {}\n- { }\n- {a: []}\n",
  };
  for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++)
    (void)assert_same_both_ways(texts[i], strlen(texts[i]));
}

static size_t check_folder(const char *dir) {
  DIR *d = opendir(dir);
  assert_non_null(d);
  size_t files = 0;
  struct dirent *ent;
  while ((ent = readdir(d)) != NULL) {
    size_t n = strlen(ent->d_name);
    if (n < 6 || strcmp(ent->d_name + n - 5, ".yaml") != 0) continue;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, ent->d_name);
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char text[1 << 20];
    size_t len = fread(text, 1, sizeof text, f);
    fclose(f);
    (void)assert_same_both_ways(text, len);
    files++;
  }
  closedir(d);
  return files;
}

static void every_shipped_scene_reads_the_same_both_ways(void **state) {
  (void)state;
  size_t files = check_folder(MR_SOURCE_DIR "/host/scenes") +
                 check_folder(MR_SOURCE_DIR "/host/scenes/hard") +
                 check_folder(MR_SOURCE_DIR "/host/scenes/modes");
  assert_true(files >= 30);
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_chain_is_read_ahead_with_libfyaml_places),
    cmocka_unit_test(lookalikes_and_bad_lines_read_as_libfyaml_reads_them),
    cmocka_unit_test(every_shipped_scene_reads_the_same_both_ways),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
