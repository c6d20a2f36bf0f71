/* What the take room's tests share: takes A and B, a book of both, a
 * punch of one into the other, and the checks on what a take holds and
 * what an error says. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mr_take.h"
#include "proc.h"
#include "take_gen.h"
#include "take_rig.h"

gen_take A, B, X;

/* Take A: 6 s at 100 Hz, calibrated 200..3800, INFO again at 3 s. */
void make_a(void) {
  gen_init(&A, 200, 3800, 0x5ce9e5ce9e000001ull);
  A.n = 600;
  A.info2_at = 3.0;
  for (size_t i = 0; i < A.n; i++)
    for (int k = 0; k < 5; k++) A.ch[i][k] = (uint16_t)(200 + (k * 300 + i * 7) % 3600);
}

/* Take B: the same glove calibrated 100..4000, sampled 5 ms off A's. */
void make_b(void) {
  gen_init(&B, 100, 4000, 0x5ce9e5ce9e000001ull);
  B.n = 590;
  B.t0 = 0.015;
  for (size_t i = 0; i < B.n; i++)
    for (int k = 0; k < 5; k++) B.ch[i][k] = (uint16_t)(100 + (k * 500 + i * 13) % 3900);
}

char *file_bytes(const char *path, size_t *len) {
  char *b = tt_read_file(path, len);
  if (b == NULL) fail_msg("cannot read %s", path);
  return b;
}

void take_path(const mr_take_book *b, const char *name, char *out) {
  char paths[MR_TAKE_MAX_GLOVES][MR_TAKE_PATH_MAX];
  size_t n;
  mr_take_error err;
  if (mr_take_book_paths(b, name, paths, MR_TAKE_MAX_GLOVES, &n, &err) != 0)
    fail_msg("%s", err.msg);
  assert_int_equal(n, 1);
  strcpy(out, paths[0]);
}

/* A book in dir holding A and B as takes "a" and "b". */
void book_ab(const char *dir, mr_take_book *b) {
  mr_take_error err;
  gen_write(&A, tt_path(dir, "a.mrec"));
  gen_write(&B, tt_path(dir, "b.mrec"));
  if (mr_take_book_open(tt_path(dir, "book"), true, b, &err) != 0) fail_msg("%s", err.msg);
  const char *pa[] = { tt_path(dir, "a.mrec") }, *pb[] = { tt_path(dir, "b.mrec") };
  if (mr_take_book_add(b, "a", pa, 1, false, NULL, &err) != 0) fail_msg("%s", err.msg);
  if (mr_take_book_add(b, "b", pb, 1, false, NULL, &err) != 0) fail_msg("%s", err.msg);
}

char *book_ab_tmp(mr_take_book *b) {
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  book_ab(dir, b);
  return dir;
}

void book_done(mr_take_book *b, char *dir) {
  mr_take_book_close(b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

void punch(mr_take_book *b, const char *name, double t_in, double t_out) {
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = "a";
  d.over = "b";
  d.name = name;
  d.arms[0] = (mr_take_arm){ 0, 1 };
  d.arms[1] = (mr_take_arm){ 0, 2 };
  d.n_arms = 2;
  d.t_in = t_in;
  d.t_out = t_out;
  mr_take_error err;
  if (mr_take_book_punch(b, &d, NULL, &err) != 0) fail_msg("%s", err.msg);
}

void load_take(const mr_take_book *b, const char *name, mr_take_rec *r) {
  char path[MR_TAKE_PATH_MAX];
  take_path(b, name, path);
  mr_take_error err;
  if (mr_take_rec_load(path, r, &err) != 0) fail_msg("%s", err.msg);
}

/* The SAMPLEs of r's frames, in order, must hold want's channels. */
void holds(const mr_take_rec *r, const gen_take *want) {
  size_t s = 0;
  for (size_t i = 0; i < r->n_frames; i++) {
    if (r->frames[i].msg.type != GP_SAMPLE) continue;
    for (int k = 0; k < 5; k++)
      if (r->frames[i].msg.u.sample.ch[k] != want->ch[s][k])
        fail_msg("sample %zu finger %d: %u, want %u", s, k, r->frames[i].msg.u.sample.ch[k],
                 want->ch[s][k]);
    s++;
  }
  assert_int_equal(s, want->n);
}

void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
}

void says(const mr_take_error *err, const char *what) {
  if (strstr(err->msg, what) == NULL) fail_msg("'%s' does not say '%s'", err->msg, what);
}
