/* The take room (mr_take): punch-in of armed channels from one take into
 * another, byte for byte against a merge this test builds from the samples
 * it generated; its replay through the show on a virtual clock; split,
 * trim, delete and restore in the take list, whose files are never
 * rewritten; smoothing and a time offset per channel. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>
#include <sys/stat.h>

#include "mr_scene.h"
#include "mr_show.h"
#include "mr_take.h"
#include "proc.h"
#include "take_gen.h"

static gen_take A, B, X; /* big: kept off the stack */

/* Take A: 6 s at 100 Hz, calibrated 200..3800, INFO again at 3 s. */
static void make_a(void) {
  gen_init(&A, 200, 3800, 0x5ce9e5ce9e000001ull);
  A.n = 600;
  A.info2_at = 3.0;
  for (size_t i = 0; i < A.n; i++)
    for (int k = 0; k < 5; k++) A.ch[i][k] = (uint16_t)(200 + (k * 300 + i * 7) % 3600);
}

/* Take B: the same glove calibrated 100..4000, sampled 5 ms off A's. */
static void make_b(void) {
  gen_init(&B, 100, 4000, 0x5ce9e5ce9e000001ull);
  B.n = 590;
  B.t0 = 0.015;
  for (size_t i = 0; i < B.n; i++)
    for (int k = 0; k < 5; k++) B.ch[i][k] = (uint16_t)(100 + (k * 500 + i * 13) % 3900);
}

static char *file_bytes(const char *path, size_t *len) {
  char *b = tt_read_file(path, len);
  if (b == NULL) fail_msg("cannot read %s", path);
  return b;
}

static void take_path(const mr_take_book *b, const char *name, char *out) {
  char paths[MR_TAKE_MAX_GLOVES][MR_TAKE_PATH_MAX];
  size_t n;
  mr_take_error err;
  if (mr_take_book_paths(b, name, paths, MR_TAKE_MAX_GLOVES, &n, &err) != 0)
    fail_msg("%s", err.msg);
  assert_int_equal(n, 1);
  strcpy(out, paths[0]);
}

/* A book in dir holding A and B as takes "a" and "b". */
static void book_ab(const char *dir, mr_take_book *b) {
  mr_take_error err;
  gen_write(&A, tt_path(dir, "a.mrec"));
  gen_write(&B, tt_path(dir, "b.mrec"));
  if (mr_take_book_open(tt_path(dir, "book"), true, b, &err) != 0) fail_msg("%s", err.msg);
  const char *pa[] = { tt_path(dir, "a.mrec") }, *pb[] = { tt_path(dir, "b.mrec") };
  if (mr_take_book_add(b, "a", pa, 1, false, NULL, &err) != 0) fail_msg("%s", err.msg);
  if (mr_take_book_add(b, "b", pb, 1, false, NULL, &err) != 0) fail_msg("%s", err.msg);
}

static void punch(mr_take_book *b, const char *name, double t_in, double t_out) {
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

/* --- the show ------------------------------------------------------------- */

enum { FRAMES = 400 };

typedef struct hashes {
  int n;
  uint64_t h[FRAMES];
} hashes;

static void frame_done(void *user, const mr_show_frame *f) {
  hashes *s = user;
  if (s->n < FRAMES) s->h[s->n++] = f->hash;
}

static const char SCENE[] = "format: 1\n"
                            "physics:\n"
                            "  effects: [control]\n"
                            "  particles: [{name: w, position: [0, 0, 0], mass: 1}]\n"
                            "  control:\n"
                            "    pose: {position: [0, 1, 0]}\n"
                            "    points: [{name: p, offset: [0.3, 0, 0]}]\n";

/* The world's state hash at every frame of the take at path replayed
 * through the show, 60 fps on a virtual clock, for 5.5 s. */
static void replay(const char *path, hashes *out) {
  mr_scene sc;
  mr_scene_error serr;
  if (mr_scene_load_text("take.yaml", SCENE, strlen(SCENE), &sc, &serr) != MR_SCENE_OK)
    fail_msg("%s", serr.text);
  mr_show_def d = mr_default_show_def();
  d.fps = 60;
  d.duration = 5.5;
  d.present = MR_PRESENT_LAND;
  char source[MR_TAKE_PATH_MAX + 8];
  snprintf(source, sizeof source, "take:%s", path);
  d.gloves[0] = source;
  d.n_gloves = 1;
  mr_virtual_clock vc = { 0 };
  mr_clock c = mr_clock_virtual(&vc);
  memset(out, 0, sizeof *out);
  mr_show_hooks h = { NULL, NULL, frame_done, NULL, out };
  mr_show *show = NULL;
  mr_show_error err;
  if (mr_show_create(&sc, &d, &c, &h, &show, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  mr_show_status st;
  while ((st = mr_show_tick(show)) == MR_SHOW_OK) {
  }
  assert_int_equal(st, MR_SHOW_ENDED);
  mr_show_result r;
  if (mr_show_destroy(show, &r, &err) != MR_SHOW_OK) fail_msg("%s", err.text);
  mr_show_result_free(&r);
  mr_scene_free(&sc);
  assert_true(out->n > 300);
}

/* --- punch-in --------------------------------------------------------------- */

/* The expected merge, from the samples themselves: A's samples, whose
 * index and middle fingers read in [2 s, 4 s) take B's newest sample at or
 * before, as B's calibration reads it, in A's counts. */
static void expected_merge(gen_take *out) {
  *out = A;
  const uint64_t in = 2000000000u, end = 4000000000u;
  for (size_t i = 0; i < A.n; i++) {
    if (A.read_ns[i] < in || A.read_ns[i] >= end) continue;
    long j = gen_at(&B, A.read_ns[i]);
    if (j < 0) continue;
    for (int k = 1; k <= 2; k++) out->ch[i][k] = gen_raw(&A, k, gen_value(&B, k, B.ch[j][k]));
  }
}

static void
a_punch_in_of_two_channels_from_2_to_4_s_stores_the_expected_merge_byte_for_byte(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  mr_take_book b;
  book_ab(dir, &b);
  punch(&b, "ab", 2.0, 4.0);
  expected_merge(&X);
  gen_write(&X, tt_path(dir, "expected.mrec"));
  char got_path[MR_TAKE_PATH_MAX];
  take_path(&b, "ab", got_path);
  size_t n_got, n_want, n_a;
  char *got = file_bytes(got_path, &n_got),
       *want = file_bytes(tt_path(dir, "expected.mrec"), &n_want);
  char *a = file_bytes(tt_path(dir, "a.mrec"), &n_a);
  assert_int_equal(n_got, n_want);
  assert_memory_equal(got, want, n_want);
  assert_int_equal(n_a, n_got);
  assert_memory_not_equal(got, a, n_a); /* the punch changed something */
  /* Replayed twice, the merged take gives the same frames; they are not A's. */
  static hashes h1, h2, ha;
  replay(got_path, &h1);
  replay(got_path, &h2);
  replay(tt_path(dir, "a.mrec"), &ha);
  assert_int_equal(h1.n, h2.n);
  assert_memory_equal(h1.h, h2.h, sizeof h1.h);
  assert_memory_not_equal(h1.h, ha.h, sizeof h1.h);
  free(got);
  free(want);
  free(a);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* B's values land in A at the value B's calibration gave them (within one
 * count of A's), and outside the window or the armed channels A's bytes
 * are A's: the frames before 2 s and after 4 s match A's file exactly. */
static void
a_punched_channel_lands_at_the_over_takes_calibrated_value_and_nothing_else_moves(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  mr_take_book b;
  book_ab(dir, &b);
  punch(&b, "ab", 2.0, 4.0);
  char path[MR_TAKE_PATH_MAX];
  take_path(&b, "ab", path);
  mr_take_rec got, a, over;
  mr_take_error err;
  if (mr_take_rec_load(path, &got, &err) != 0 ||
      mr_take_rec_load(tt_path(dir, "a.mrec"), &a, &err) != 0 ||
      mr_take_rec_load(tt_path(dir, "b.mrec"), &over, &err) != 0)
    fail_msg("%s", err.msg);
  assert_int_equal(got.n_frames, a.n_frames);
  int inside = 0;
  for (size_t i = 0; i < got.n_frames; i++) {
    const mr_take_frame *f = &got.frames[i], *fa = &a.frames[i];
    assert_int_equal(f->len, fa->len);
    bool in = f->t_ns >= 2000000000u && f->t_ns < 4000000000u && f->msg.type == GP_SAMPLE;
    for (int k = 0; k < 5 && f->msg.type == GP_SAMPLE; k++) {
      if (!in || k == 0 || k > 2) {
        assert_int_equal(f->msg.u.sample.ch[k], fa->msg.u.sample.ch[k]);
        continue;
      }
      long j = gen_at(&B, f->t_ns);
      long jb = mr_take_rec_sample_at(&over, f->t_ns);
      assert_true(jb >= 0);
      assert_int_equal(over.frames[jb].msg.u.sample.seq, j);
      double want = gen_value(&B, k, B.ch[j][k]);
      assert_true(fabs(mr_take_rec_value(&got, i, k) - want) <= 1.0 / 3600.0);
      inside++;
    }
    if (!in) assert_memory_equal(got.data + f->off, a.data + fa->off, f->len);
  }
  assert_int_equal(inside, 2 * 200);
  assert_int_equal(got.len, a.len);
  mr_take_rec_free(&got);
  mr_take_rec_free(&a);
  mr_take_rec_free(&over);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* Over a take read at the very times of the base, each punched SAMPLE
 * takes the over SAMPLE read at its own time, not the one before. */
static void a_punch_takes_the_over_sample_read_at_the_same_time(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  B.t0 = A.t0;
  mr_take_book b;
  book_ab(dir, &b);
  punch(&b, "ab", 2.0, 4.0);
  expected_merge(&X);
  gen_write(&X, tt_path(dir, "expected.mrec"));
  char got_path[MR_TAKE_PATH_MAX];
  take_path(&b, "ab", got_path);
  size_t n_got, n_want;
  char *got = file_bytes(got_path, &n_got),
       *want = file_bytes(tt_path(dir, "expected.mrec"), &n_want);
  assert_int_equal(n_got, n_want);
  assert_memory_equal(got, want, n_want);
  free(got);
  free(want);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* --- the list --------------------------------------------------------------- */

/* Every file in the book's folder with its bytes and mtime, to compare
 * before and after each operation. */
typedef struct snapshot {
  int n;
  char name[32][80];
  char *bytes[32];
  size_t len[32];
  struct timespec mtime[32];
} snapshot;

static void snap(const char *dir, snapshot *s) {
  memset(s, 0, sizeof *s);
  DIR *d = opendir(dir);
  assert_non_null(d);
  for (struct dirent *e; s->n < 32 && (e = readdir(d)) != NULL;) {
    if (strstr(e->d_name, ".mrec") == NULL) continue;
    snprintf(s->name[s->n], sizeof s->name[0], "%.70s", e->d_name);
    const char *path = tt_path(dir, s->name[s->n]);
    s->bytes[s->n] = file_bytes(path, &s->len[s->n]);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    s->mtime[s->n] = st.st_mtim;
    s->n++;
  }
  closedir(d);
}

/* Every file of before is in after, byte for byte, with its mtime. */
static void unchanged(const snapshot *before, const snapshot *after) {
  for (int i = 0; i < before->n; i++) {
    int j = 0;
    while (j < after->n && strcmp(after->name[j], before->name[i]) != 0) j++;
    if (j == after->n) fail_msg("%s is gone", before->name[i]);
    assert_int_equal(before->len[i], after->len[j]);
    assert_memory_equal(before->bytes[i], after->bytes[j], before->len[i]);
    assert_int_equal(before->mtime[i].tv_sec, after->mtime[j].tv_sec);
    assert_int_equal(before->mtime[i].tv_nsec, after->mtime[j].tv_nsec);
  }
}

static void unsnap(snapshot *s) {
  for (int i = 0; i < s->n; i++) free(s->bytes[i]);
}

static void load_take(const mr_take_book *b, const char *name, mr_take_rec *r) {
  char path[MR_TAKE_PATH_MAX];
  take_path(b, name, path);
  mr_take_error err;
  if (mr_take_rec_load(path, r, &err) != 0) fail_msg("%s", err.msg);
}

/* Split at 3.5 s: the first part is A's chunks before 3.5 s as they were;
 * the second starts at 0 with the INFO A sent at 3 s, then A's chunks from
 * 3.5 s on, 3.5 s earlier. Trim [1.5 s, 2.5 s) alike, led by A's first
 * INFO. */
static void split_and_trim_keep_times_lengths_and_a_leading_info(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  A.info2.cal_max[3] = 3700; /* the second INFO differs from the first */
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_error err;
  mr_take_made m;
  if (mr_take_book_split(&b, "a", 3.5, NULL, NULL, &m, &err) != 0) fail_msg("%s", err.msg);
  mr_take_rec a, p1, p2, t;
  load_take(&b, "a", &a);
  load_take(&b, m.name, &p1);
  load_take(&b, m.name2, &p2);
  size_t cut = 0;
  while (a.chunks[cut].t_ns < 3500000000u) cut++;
  assert_int_equal(p1.n_chunks, cut);
  assert_int_equal(p1.len, a.chunks[cut].off);
  assert_memory_equal(p1.data, a.data, p1.len);
  assert_int_equal(p2.n_chunks, a.n_chunks - cut + 1);
  assert_int_equal(p2.frames[0].msg.type, GP_INFO);
  assert_int_equal(p2.chunks[0].t_ns, 0);
  assert_int_equal(p2.frames[0].msg.u.info.cal_max[3], 3700);
  for (size_t c = cut; c < a.n_chunks; c++) {
    assert_int_equal(p2.chunks[c - cut + 1].t_ns, a.chunks[c].t_ns - 3500000000u);
    assert_int_equal(p2.chunks[c - cut + 1].len, a.chunks[c].len);
  }
  assert_int_equal(p2.len, p2.chunks[0].len + a.len - a.chunks[cut].off);
  assert_true(fabs(mr_take_book_find(&b, m.name2)->duration - (mr_take_rec_duration(&a) - 3.5)) <
              1e-9);
  /* Both parts name the cut in their lineage. */
  assert_true(mr_take_book_find(&b, m.name)->t0 == 3.5);
  assert_int_equal(mr_take_book_find(&b, m.name)->part, 1);
  assert_true(mr_take_book_find(&b, m.name2)->t0 == 3.5);
  assert_int_equal(mr_take_book_find(&b, m.name2)->part, 2);
  if (mr_take_book_trim(&b, "a", 1.5, 2.5, "mid", NULL, &err) != 0) fail_msg("%s", err.msg);
  load_take(&b, "mid", &t);
  assert_int_equal(t.frames[0].msg.type, GP_INFO);
  assert_int_equal(t.frames[0].msg.u.info.cal_max[3], 3800);
  size_t samples = 0;
  for (size_t i = 0; i < t.n_frames; i++) samples += t.frames[i].msg.type == GP_SAMPLE;
  assert_int_equal(samples, 100);
  assert_true(t.chunks[t.n_chunks - 1].t_ns < 1000000000u);
  mr_take_rec_free(&a);
  mr_take_rec_free(&p1);
  mr_take_rec_free(&p2);
  mr_take_rec_free(&t);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* Delete hides a take (its files stay, it still resolves), restore brings
 * it back, rename moves only the name; across punch, split, trim, smooth,
 * offset, scale, delete, restore and rename no take's file is rewritten. */
static void delete_hides_restore_returns_and_no_take_file_is_ever_rewritten(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  mr_take_book b;
  book_ab(dir, &b);
  const char *bd = tt_path(dir, "book");
  char keep[MR_TAKE_PATH_MAX];
  strcpy(keep, bd);
  snapshot s0, s1;
  mr_take_error err;
  double off[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS] = { { 0, 0.05 } };
  mr_take_smooth_def sd = mr_default_take_smooth_def();
  for (int step = 0; step < 9; step++) {
    snap(keep, &s0);
    int rc = 0;
    switch (step) {
    case 0:
      punch(&b, "p", 1.0, 2.0);
      break;
    case 1:
      rc = mr_take_book_split(&b, "p", 3.0, "s1", "s2", NULL, &err);
      break;
    case 2:
      rc = mr_take_book_trim(&b, "a", 1.0, 2.0, "t", NULL, &err);
      break;
    case 3:
      rc = mr_take_book_smooth(&b, "a", &sd, "sm", NULL, &err);
      break;
    case 4:
      rc = mr_take_book_offset(&b, "a", off, "of", NULL, &err);
      break;
    case 5:
      rc = mr_take_book_scale(&b, "a", 0.25, "sc", NULL, &err);
      break;
    case 6:
      rc = mr_take_book_delete(&b, "a", &err);
      break;
    case 7:
      rc = mr_take_book_rename(&b, "a", "first", &err);
      break;
    case 8:
      rc = mr_take_book_restore(&b, "first", &err);
      break;
    }
    if (rc != 0) fail_msg("step %d: %s", step, err.msg);
    snap(keep, &s1);
    unchanged(&s0, &s1);
    unsnap(&s0);
    unsnap(&s1);
  }
  mr_take_book_close(&b);
  /* Reopened: the list says what was done. */
  if (mr_take_book_open(keep, false, &b, &err) != 0) fail_msg("%s", err.msg);
  assert_null(mr_take_book_find(&b, "a"));
  const mr_take_entry *first = mr_take_book_find(&b, "first");
  assert_non_null(first);
  assert_false(first->deleted);
  assert_int_equal(mr_take_book_find(&b, "t")->source_id, first->id);
  assert_true(mr_take_book_find(&b, "t")->scene_hash == first->scene_hash);
  assert_true(mr_take_book_find(&b, "sc")->scene_hash == 0x5ce9e5ce9e000001ull);
  assert_int_equal(mr_take_book_find(&b, "p")->over_id, mr_take_book_find(&b, "b")->id);
  assert_true(fabs(mr_take_book_find(&b, "sc")->factor - 0.25) < 1e-12);
  assert_int_equal(mr_take_book_delete(&b, "b", &err), 0);
  mr_take_book_close(&b);
  if (mr_take_book_open(keep, false, &b, &err) != 0) fail_msg("%s", err.msg);
  assert_true(mr_take_book_find(&b, "b")->deleted);
  char ref[MR_TAKE_PATH_MAX + 8], paths[8][MR_TAKE_PATH_MAX];
  size_t n;
  snprintf(ref, sizeof ref, "%s:b", keep);
  assert_int_equal(mr_take_resolve(ref, paths, 8, &n, &err), 1);
  /* "DIR:" names no take, nor does a folder without a list: both are files. */
  snprintf(ref, sizeof ref, "%s:", keep);
  assert_int_equal(mr_take_resolve(ref, paths, 8, &n, &err), 0);
  snprintf(ref, sizeof ref, "%s:b", dir);
  assert_int_equal(mr_take_resolve(ref, paths, 8, &n, &err), 0);
  struct stat st;
  assert_int_equal(stat(paths[0], &st), 0);
  assert_int_equal(mr_take_book_check_name(&b, "b", &err), -1); /* still taken */
  assert_non_null(strstr(err.msg, "a take named 'b' is already there (deleted; restore it"));
  assert_int_equal(mr_take_book_delete(&b, "b", &err), -1);
  assert_non_null(strstr(err.msg, "take 'b' is already deleted"));
  assert_int_equal(mr_take_book_restore(&b, "b", &err), 0);
  assert_false(mr_take_book_find(&b, "b")->deleted);
  assert_int_equal(mr_take_book_check_name(&b, "b", &err), -1);
  assert_null(strstr(err.msg, "deleted"));
  mr_take_book_close(&b);
  tt_rmdir(keep);
  tt_rmdir(dir);
  free(dir);
}

/* --- filters ---------------------------------------------------------------- */

/* The One Euro filter as its paper writes it, apart from mr_control's. */
typedef struct euro {
  double x, dx, t;
  int started;
} euro;

static double euro_alpha(double cutoff, double dt) {
  return 1.0 / (1.0 + 1.0 / (2.0 * 3.14159265358979323846 * cutoff) / dt);
}

static double euro_step(euro *e, double x, double t, double fmin, double beta, double fd) {
  if (!e->started) {
    *e = (euro){ x, 0.0, t, 1 };
    return x;
  }
  double dt = t - e->t, ad = euro_alpha(fd, dt);
  e->dx = ad * (x - e->x) / dt + (1.0 - ad) * e->dx;
  double a = euro_alpha(fmin + beta * fabs(e->dx), dt);
  e->x = a * x + (1.0 - a) * e->x;
  e->t = t;
  return e->x;
}

/* The SAMPLEs of r's frames, in order, must hold want's channels. */
static void holds(const mr_take_rec *r, const gen_take *want) {
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

/* Smoothing with min_cutoff 2.5 Hz, beta 0.3, d_cutoff 1.7 Hz on the
 * index and ring fingers gives what the filter computed here gives, and
 * leaves the other fingers' counts as they were. */
static void
smoothing_changes_only_the_chosen_channels_as_an_independent_one_euro_does(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_smooth_def d = mr_default_take_smooth_def();
  d.min_cutoff = 2.5;
  d.beta = 0.3;
  d.d_cutoff = 1.7;
  mr_take_error err;
  if (mr_take_arms_parse("0:index,0:3", d.channels, MR_TAKE_MAX_ARMS, &d.n_channels, &err) != 0)
    fail_msg("%s", err.msg);
  if (mr_take_book_smooth(&b, "a", &d, "sm", NULL, &err) != 0) fail_msg("%s", err.msg);
  X = A;
  int changed = 0;
  for (int k = 1; k <= 3; k += 2) {
    euro e = { 0 };
    for (size_t i = 0; i < A.n; i++) {
      double v =
          euro_step(&e, gen_value(&A, k, A.ch[i][k]), (double)A.read_ns[i] / 1e9, 2.5, 0.3, 1.7);
      X.ch[i][k] = gen_raw(&A, k, v);
      changed += X.ch[i][k] != A.ch[i][k];
    }
  }
  assert_true(changed > 100);
  mr_take_rec r;
  load_take(&b, "sm", &r);
  holds(&r, &X);
  mr_take_rec_free(&r);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* With no channels chosen, smoothing filters all five fingers, each by
 * the default filter (min_cutoff 1 Hz, beta 0, d_cutoff 1 Hz). */
static void smoothing_with_no_channels_chosen_filters_every_finger(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_smooth_def d = mr_default_take_smooth_def();
  mr_take_error err;
  if (mr_take_book_smooth(&b, "a", &d, "sm", NULL, &err) != 0) fail_msg("%s", err.msg);
  X = A;
  for (int k = 0; k < 5; k++) {
    euro e = { 0 };
    for (size_t i = 0; i < A.n; i++) {
      double v =
          euro_step(&e, gen_value(&A, k, A.ch[i][k]), (double)A.read_ns[i] / 1e9, 1.0, 0.0, 1.0);
      X.ch[i][k] = gen_raw(&A, k, v);
    }
  }
  mr_take_rec r;
  load_take(&b, "sm", &r);
  holds(&r, &X);
  mr_take_rec_free(&r);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* An offset of -0.137 s on the middle finger: at t it holds A's value at
 * t + 0.137 s (the last sample's at the end); the other fingers stay. */
static void an_offset_shifts_one_channel_and_leaves_the_others(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  mr_take_book b;
  book_ab(dir, &b);
  double off[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS] = { { 0 } };
  off[0][2] = -0.137;
  mr_take_error err;
  if (mr_take_book_offset(&b, "a", off, NULL, NULL, &err) != 0) fail_msg("%s", err.msg);
  X = A;
  for (size_t i = 0; i < A.n; i++) X.ch[i][2] = A.ch[gen_at(&A, A.read_ns[i] + 137000000u)][2];
  mr_take_rec r;
  load_take(&b, "take-1", &r);
  holds(&r, &X);
  mr_take_rec_free(&r);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* Scaling by 0.25 multiplies every chunk time and rounds to the ns. */
static void scaling_multiplies_every_chunk_time_and_keeps_the_bytes(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_error err;
  if (mr_take_book_scale(&b, "a", 0.25, "q", NULL, &err) != 0) fail_msg("%s", err.msg);
  mr_take_rec a, q;
  load_take(&b, "a", &a);
  load_take(&b, "q", &q);
  assert_int_equal(a.n_chunks, q.n_chunks);
  assert_memory_equal(a.data, q.data, a.len);
  for (size_t c = 0; c < a.n_chunks; c++)
    assert_int_equal(q.chunks[c].t_ns, (uint64_t)llround((double)a.chunks[c].t_ns * 0.25));
  assert_true(fabs(mr_take_book_find(&b, "q")->duration - 0.25 * mr_take_rec_duration(&a)) < 1e-9);
  mr_take_rec_free(&a);
  mr_take_rec_free(&q);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* --- bad input -------------------------------------------------------------- */

static void write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
}

static void says(const mr_take_error *err, const char *what) {
  if (strstr(err->msg, what) == NULL) fail_msg("'%s' does not say '%s'", err->msg, what);
}

/* A malformed takes.json (not JSON; a take without files; an id that is
 * no number) and a take whose file is gone give errors naming the file
 * and what is wrong. */
static void a_malformed_list_or_a_missing_take_file_is_named(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  char book[MR_TAKE_PATH_MAX];
  strcpy(book, tt_path(dir, "book"));
  assert_int_equal(mkdir(book, 0777), 0);
  mr_take_book b;
  mr_take_error err;
  write_text(tt_path(book, "takes.json"), "{ \"format\": 1, \"next_id\": 2, \"takes\": [ ");
  assert_int_equal(mr_take_book_open(book, false, &b, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_FORMAT);
  says(&err, "takes.json: not JSON");
  write_text(tt_path(book, "takes.json"),
             "{\"format\": 1, \"next_id\": 2, \"takes\": [{\"name\": \"x\", \"id\": 1, "
             "\"duration\": 1, \"scene_hash\": \"0\", \"created_unix\": 0, \"deleted\": false, "
             "\"made\": {\"how\": \"recorded\"}}]}");
  assert_int_equal(mr_take_book_open(book, false, &b, &err), -1);
  says(&err, "takes.json: takes[0].files: expected a list");
  write_text(tt_path(book, "takes.json"),
             "{\"format\": 1, \"next_id\": 2, \"takes\": [{\"name\": \"x\", \"id\": \"one\", "
             "\"files\": [\"t0001-g0.mrec\"], \"duration\": 1, \"scene_hash\": \"0\", "
             "\"created_unix\": 0, \"deleted\": false, \"made\": {\"how\": \"recorded\"}}]}");
  assert_int_equal(mr_take_book_open(book, false, &b, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_FORMAT);
  says(&err, "takes.json: takes[0].id: expected a number");
  write_text(tt_path(book, "takes.json"),
             "{\"format\": 1, \"next_id\": 2, \"takes\": [{\"name\": \"x\", \"id\": 1, "
             "\"files\": [\"t0001-g0.mrec\"], \"duration\": 1, \"scene_hash\": \"0\", "
             "\"created_unix\": 0, \"deleted\": false, \"made\": {\"how\": \"recorded\"}}]}");
  if (mr_take_book_open(book, false, &b, &err) != 0) fail_msg("%s", err.msg);
  char paths[8][MR_TAKE_PATH_MAX];
  size_t n;
  assert_int_equal(mr_take_book_paths(&b, "x", paths, 8, &n, &err), -1);
  says(&err, "t0001-g0.mrec");
  assert_int_equal(mr_take_book_trim(&b, "x", 0, 1, NULL, NULL, &err), -1);
  says(&err, "t0001-g0.mrec");
  mr_take_book_close(&b);
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

/* Each field of takes.json is checked: a list of another format or a
 * next_id below 1, and an entry whose name is too long, whose id is not
 * whole or not below next_id or given twice, with no files, an empty scene
 * hash or an armed glove past 7, is refused naming the entry and field. */
static void each_field_of_a_take_list_is_checked(void **state) {
  (void)state;
  static const char N64[] = "nnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnnn";
  static const char REC[] = "{\"how\": \"recorded\"}";
  static const char ARMS8[] =
      "{\"how\": \"punch\", \"base\": 1, \"over\": 1, \"in\": 0, \"out\": 1, "
      "\"arms\": [[8, 0]]}";
  static const char TWICE[] = ", {\"name\": \"y\", \"id\": 1, \"files\": [\"t0001-g0.mrec\"], "
                              "\"duration\": 1, \"scene_hash\": \"0\", \"created_unix\": 0, "
                              "\"deleted\": false, \"made\": {\"how\": \"recorded\"}}";
  static const char F1[] = "[\"t0001-g0.mrec\"]";
  static const struct {
    const char *format, *next_id, *name, *id, *files, *hash, *made, *more, *what;
  } cases[] = {
    { "2", "2", "x", "1", F1, "0", REC, "", "expected an object with format 1" },
    { "1", "0", "x", "1", F1, "0", REC, "", "expected an object with format 1" },
    { "1", "2", N64, "1", F1, "0", REC, "", "takes[0].name: expected a string" },
    { "1", "2", "x", "1.5", F1, "0", REC, "", "takes[0].id: expected a whole number" },
    { "1", "2", "x", "2", F1, "0", REC, "", "takes[0].id: not below next_id" },
    { "1", "2", "x", "1", F1, "0", REC, TWICE, "takes[1].name: a name or id given twice" },
    { "1", "2", "x", "1", "[]", "0", REC, "", "takes[0].files: expected a list of 1..8" },
    { "1", "2", "x", "1", F1, "", REC, "", "takes[0].scene_hash: expected 16 hex digits" },
    { "1", "2", "x", "1", F1, "0", ARMS8, "", "takes[0].arms: expected [glove 0..7, finger" },
  };
  char *dir = tt_tmpdir();
  char book[MR_TAKE_PATH_MAX], text[1200];
  strcpy(book, tt_path(dir, "book"));
  assert_int_equal(mkdir(book, 0777), 0);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    snprintf(text, sizeof text,
             "{\"format\": %s, \"next_id\": %s, \"takes\": [{\"name\": \"%s\", \"id\": %s, "
             "\"files\": %s, \"duration\": 1, \"scene_hash\": \"%s\", \"created_unix\": 0, "
             "\"deleted\": false, \"made\": %s}%s]}",
             cases[i].format, cases[i].next_id, cases[i].name, cases[i].id, cases[i].files,
             cases[i].hash, cases[i].made, cases[i].more);
    write_text(tt_path(book, "takes.json"), text);
    mr_take_book b;
    mr_take_error err;
    if (mr_take_book_open(book, false, &b, &err) == 0) fail_msg("case %zu was read", i);
    assert_int_equal(err.status, MR_TAKE_ERR_FORMAT);
    says(&err, cases[i].what);
  }
  assert_string_equal(mr_take_how_name(MR_TAKE_SCALED), "scale");
  assert_string_equal(mr_take_how_name((mr_take_how)(MR_TAKE_SCALED + 1)), "?");
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

/* A list of many takes, its takes.json longer than twice the reader's
 * first 4 KiB, reads back whole. */
static void a_long_take_list_reads_back_whole(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  A.n = 10;
  A.info2_at = 0;
  gen_write(&A, tt_path(dir, "a.mrec"));
  char pa[MR_TAKE_PATH_MAX], book[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  const char *p[] = { pa };
  mr_take_book b;
  mr_take_error err;
  if (mr_take_book_open(book, true, &b, &err) != 0) fail_msg("%s", err.msg);
  for (int i = 0; i < 40; i++)
    if (mr_take_book_add(&b, NULL, p, 1, false, NULL, &err) != 0) fail_msg("%s", err.msg);
  mr_take_book_close(&b);
  size_t len;
  free(file_bytes(tt_path(book, "takes.json"), &len));
  assert_true(len > 8192);
  if (mr_take_book_open(book, false, &b, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(b.n, 40);
  assert_int_equal(b.next_id, 41);
  assert_int_equal(mr_take_book_find(&b, "take-40")->id, 40);
  mr_take_book_close(&b);
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

/* A take cut off mid-chunk is used up to its last whole chunk, and the
 * operation says so. */
static void a_cut_off_take_is_used_up_to_its_last_whole_chunk_and_says_so(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  mr_take_book b;
  book_ab(dir, &b);
  size_t len;
  char *bytes = file_bytes(tt_path(dir, "a.mrec"), &len);
  FILE *f = fopen(tt_path(dir, "cut.mrec"), "wb");
  fwrite(bytes, 1, len - 7, f);
  fclose(f);
  free(bytes);
  mr_take_error err;
  mr_take_made m;
  const char *p[] = { tt_path(dir, "cut.mrec") };
  if (mr_take_book_add(&b, "cut", p, 1, false, &m, &err) != 0) fail_msg("%s", err.msg);
  if (strstr(m.note, "last whole chunk") == NULL) fail_msg("note: '%s'", m.note);
  if (mr_take_book_trim(&b, "cut", 0.5, 9.0, NULL, &m, &err) != 0) fail_msg("%s", err.msg);
  if (strstr(m.note, "cut.mrec") == NULL && strstr(m.note, ".mrec") == NULL)
    fail_msg("note: '%s'", m.note);
  mr_take_rec r;
  load_take(&b, m.name, &r);
  assert_false(r.truncated);
  assert_int_equal(r.frames[r.n_frames - 1].msg.u.sample.seq, A.n - 2);
  mr_take_rec_free(&r);
  /* Of two gloves cut off, the note names the first. */
  const char *p2[] = { p[0], p[0] };
  if (mr_take_book_add(&b, "cut2", p2, 2, false, &m, &err) != 0) fail_msg("%s", err.msg);
  if (mr_take_book_trim(&b, "cut2", 0.5, 9.0, NULL, &m, &err) != 0) fail_msg("%s", err.msg);
  if (strstr(m.note, "-g0.mrec") == NULL) fail_msg("note: '%s'", m.note);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* Takes of different scenes, unknown names, bad names and absurd numbers
 * are refused, each with a message saying what. */
static void different_scenes_unknown_names_and_absurd_numbers_are_refused(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  B.scene = 0x00000000beefcafeull;
  mr_take_book b;
  book_ab(dir, &b);
  /* The list writes each scene hash as 16 hex digits, leading zeros too. */
  size_t len;
  char *list = file_bytes(tt_path(tt_path(dir, "book"), "takes.json"), &len);
  if (strstr(list, "\"00000000beefcafe\"") == NULL) fail_msg("%s", list);
  free(list);
  mr_take_error err;
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = "a";
  d.over = "b";
  d.arms[0] = (mr_take_arm){ 0, 1 };
  d.n_arms = 1;
  d.t_in = 1;
  d.t_out = 2;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_SCENE);
  says(&err, "5ce9e5ce9e000001");
  says(&err, "00000000beefcafe");
  /* Nor is a take of two gloves recorded against different scenes, or
   * one whose file is missing, added to the list. */
  char pa[MR_TAKE_PATH_MAX], pb[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  snprintf(pb, sizeof pb, "%s", tt_path(dir, "b.mrec"));
  const char *both[] = { pa, pb }, *gone[] = { pa, tt_path(dir, "gone.mrec") };
  assert_int_equal(mr_take_book_add(&b, "ab", both, 2, false, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_SCENE);
  says(&err, "b.mrec: recorded against scene 00000000beefcafe");
  says(&err, "5ce9e5ce9e000001");
  assert_int_equal(mr_take_book_add(&b, "gone", gone, 2, false, NULL, &err), -1);
  says(&err, "gone.mrec");
  d.over = "nope";
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_NAME);
  says(&err, "'nope'");
  d.over = "a";
  d.t_in = 3;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  d.t_in = NAN;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  d.t_in = 1;
  d.arms[0].glove = 1; /* the take has one glove */
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  says(&err, "1:1");
  mr_take_punch_def raw;
  memset(&raw, 0, sizeof raw);
  assert_int_equal(mr_take_book_punch(&b, &raw, NULL, &err), -1);
  says(&err, "mr_default_take_punch_def");
  mr_take_smooth_def sraw;
  memset(&sraw, 0, sizeof sraw);
  assert_int_equal(mr_take_book_smooth(&b, "a", &sraw, NULL, NULL, &err), -1);
  says(&err, "mr_default_take_smooth_def");
  /* Channels of a glove the take has not, as the punch's armed ones. */
  mr_take_smooth_def sd = mr_default_take_smooth_def();
  sd.channels[0] = (mr_take_arm){ 1, 2 };
  sd.n_channels = 1;
  assert_int_equal(mr_take_book_smooth(&b, "a", &sd, NULL, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "channel 1:2: take 'a' has gloves 0..0");
  double off[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS] = { { 0 } };
  off[0][1] = 0.5;
  off[3][4] = -0.25;
  assert_int_equal(mr_take_book_offset(&b, "a", off, NULL, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "channel 3:4: take 'a' has gloves 0..0");
  assert_int_equal(mr_take_book_scale(&b, "a", -0.5, NULL, NULL, &err), -1);
  says(&err, "-0.5");
  assert_int_equal(mr_take_book_scale(&b, "a", NAN, NULL, NULL, &err), -1);
  assert_int_equal(mr_take_book_split(&b, "a", NAN, NULL, NULL, NULL, &err), -1);
  assert_int_equal(mr_take_book_split(&b, "a", 60.0, NULL, NULL, NULL, &err), -1);
  assert_int_equal(mr_take_book_trim(&b, "a", 2, 1, NULL, NULL, &err), -1);
  assert_int_equal(mr_take_book_rename(&b, "a", "x/y", &err), -1);
  assert_int_equal(mr_take_book_rename(&b, "a", "", &err), -1);
  assert_int_equal(mr_take_book_rename(&b, "a", "b", &err), -1);
  assert_int_equal(mr_take_book_restore(&b, "a", &err), -1);
  says(&err, "take 'a' is not deleted");
  size_t n;
  mr_take_arm arms[4];
  assert_int_equal(mr_take_arms_parse("0:pinky", arms, 4, &n, &err), -1);
  assert_int_equal(mr_take_arms_parse("9:1", arms, 4, &n, &err), -1);
  /* Nothing refused left a take behind. */
  assert_int_equal(b.n, 2);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* Without a valid range, a take reads raw counts by its glove's ADC full
 * scale, as the host does (host/glove): 2^bits - 1 for 1..16 bits, the
 * 12-bit scale for any other number and before any INFO. */
static void a_take_reads_counts_by_the_adc_full_scale_its_info_gives(void **state) {
  (void)state;
  static const struct {
    int bits;
    double full;
  } cases[] = { { 1, 1 }, { 10, 1023 }, { 12, 4095 }, { 16, 65535 }, { 0, 4095 }, { 17, 4095 } };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    gp_info info;
    memset(&info, 0, sizeof info);
    info.adc_bits = (uint8_t)cases[i].bits;
    mr_take_cal c = mr_take_cal_of(&info);
    if (c.full != cases[i].full || mr_take_cal_value(&c, 2, 1) != 1.0 / cases[i].full)
      fail_msg("%d bits: full scale %g, expected %g", cases[i].bits, c.full, cases[i].full);
    assert_int_equal(mr_take_cal_raw(&c, 2, 1.0 / cases[i].full), 1);
  }
  mr_take_cal none = mr_take_cal_of(NULL);
  assert_true(none.full == 4095.0);
}

/* A take may have one file per glove, up to MR_TAKE_MAX_GLOVES: the most
 * is added, named and listed whole, and read back so from the list; one
 * more, or none, is refused. All 40 channels of the most gloves may be
 * armed or smoothed at once, 41 not. */
static void a_take_of_the_most_gloves_is_added_and_one_more_is_refused(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  gen_write(&A, tt_path(dir, "a.mrec"));
  char pa[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  const char *paths[MR_TAKE_MAX_GLOVES + 1];
  for (int g = 0; g <= MR_TAKE_MAX_GLOVES; g++) paths[g] = pa;
  mr_take_book b;
  mr_take_error err;
  char book[MR_TAKE_PATH_MAX];
  snprintf(book, sizeof book, "%s", tt_path(dir, "book"));
  if (mr_take_book_open(book, true, &b, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(mr_take_book_add(&b, "nine", paths, MR_TAKE_MAX_GLOVES + 1, false, NULL, &err),
                   -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "got 9");
  assert_int_equal(mr_take_book_add(&b, "none", paths, 0, false, NULL, &err), -1);
  if (mr_take_book_add(&b, "eight", paths, MR_TAKE_MAX_GLOVES, false, NULL, &err) != 0)
    fail_msg("%s", err.msg);
  assert_int_equal(b.n, 1);
  mr_take_book_close(&b);
  if (mr_take_book_open(book, false, &b, &err) != 0) fail_msg("%s", err.msg);
  const mr_take_entry *e = mr_take_book_find(&b, "eight");
  assert_non_null(e);
  assert_int_equal(e->how, MR_TAKE_RECORDED);
  assert_int_equal(e->source_id, 0);
  char got[MR_TAKE_MAX_GLOVES][MR_TAKE_PATH_MAX];
  size_t n;
  if (mr_take_book_paths(&b, "eight", got, MR_TAKE_MAX_GLOVES, &n, &err) != 0)
    fail_msg("%s", err.msg);
  assert_int_equal(n, MR_TAKE_MAX_GLOVES);
  size_t len_a, len;
  char *want = file_bytes(pa, &len_a);
  for (int g = 0; g < MR_TAKE_MAX_GLOVES; g++) {
    char name[32];
    snprintf(name, sizeof name, "-g%d.mrec", g);
    if (strstr(got[g], name) == NULL) fail_msg("glove %d's file is %s", g, got[g]);
    char *bytes = file_bytes(got[g], &len);
    assert_int_equal(len, len_a);
    assert_memory_equal(bytes, want, len);
    free(bytes);
  }
  free(want);
  /* All 40 of its channels may be armed or smoothed at once, no more. */
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = d.over = "eight";
  d.t_in = 1.0;
  d.t_out = 2.0;
  mr_take_smooth_def sd = mr_default_take_smooth_def();
  for (int g = 0; g < MR_TAKE_MAX_GLOVES; g++)
    for (int k = 0; k < MR_TAKE_CHANNELS; k++)
      d.arms[d.n_arms++] = sd.channels[sd.n_channels++] = (mr_take_arm){ g, k };
  if (mr_take_book_punch(&b, &d, NULL, &err) != 0) fail_msg("%s", err.msg);
  if (mr_take_book_smooth(&b, "eight", &sd, NULL, NULL, &err) != 0) fail_msg("%s", err.msg);
  d.n_arms = sd.n_channels = MR_TAKE_MAX_ARMS + 1;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  says(&err, "expected 1..40 armed channels, got 41");
  assert_int_equal(mr_take_book_smooth(&b, "eight", &sd, NULL, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "expected at most 40 channels to smooth, got 41");
  assert_int_equal(b.n, 3);
  mr_take_book_close(&b);
  tt_rmdir(book);
  tt_rmdir(dir);
  free(dir);
}

/* A value goes back to the nearest count of its calibration, clamped to
 * 0..4095 (one count past either end is that end), NaN as the low end; an
 * INFO whose range is empty (max == min) reads by the full scale. */
static void a_value_goes_back_to_the_nearest_count_within_the_adc_range(void **state) {
  (void)state;
  gp_info info = gp_default_glove_info();
  info.cal_state = GP_CAL_VALID;
  for (int k = 0; k < 5; k++) {
    info.cal_min[k] = 200;
    info.cal_max[k] = 3800;
  }
  info.cal_max[4] = 200;
  mr_take_cal c = mr_take_cal_of(&info);
  assert_true(c.ranged[1]);
  assert_int_equal(mr_take_cal_raw(&c, 1, 0.5), 2000);
  assert_int_equal(mr_take_cal_raw(&c, 1, NAN), 200);
  assert_false(c.ranged[4]);
  assert_true(mr_take_cal_value(&c, 4, 1000) == 1000.0 / 4095.0);
  assert_int_equal(mr_take_cal_raw(&c, 4, NAN), 0);
  assert_int_equal(mr_take_cal_raw(&c, 4, -1.0 / 4095.0), 0);
  assert_int_equal(mr_take_cal_raw(&c, 4, 1.0), 4095);
  assert_int_equal(mr_take_cal_raw(&c, 4, 4096.0 / 4095.0), 4095);
}

/* An INFO announcing another build's spec hash is not a frame: its range
 * is not applied, and the SAMPLEs read by the 12-bit full scale. */
static void an_info_of_another_spec_hash_is_not_a_frame(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  A.info.spec_hash ^= 1u;
  A.info2 = A.info;
  gen_write(&A, tt_path(dir, "a.mrec"));
  mr_take_rec r;
  mr_take_error err;
  if (mr_take_rec_load(tt_path(dir, "a.mrec"), &r, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(r.n_frames, A.n);
  assert_int_equal(r.frames[0].msg.type, GP_SAMPLE);
  assert_true(mr_take_rec_value(&r, 0, 1) == A.ch[0][1] / 4095.0);
  mr_take_rec_free(&r);
  tt_rmdir(dir);
  free(dir);
}

/* --- chunks that cut frames ------------------------------------------------- */

/* Writes to path a take of A's calibration whose chunks cut its frames
 * unevenly (times in ms): the INFO at 0; sample 0 but its delimiter at 10,
 * the delimiter alone at 30; sample 1's first 10 bytes at 40, the rest at
 * 50; samples 2 and 3 in one chunk at 60; sample 4 at 70. Sample s holds
 * 1000 + 100 s + 10 k in finger k. */
static void write_cut_take(const char *path) {
  gen_init(&A, 200, 3800, 0);
  mr_rec_writer w;
  mr_io_error ie;
  if (mr_rec_writer_open_scene(&w, path, GP_SPEC_HASH, 0, 0, &ie) != 0) fail_msg("%s", ie.msg);
  uint8_t s[5][GP_MAX_WIRE], info[GP_MAX_WIRE], two[2 * GP_MAX_WIRE];
  size_t n[5], ni = gp_glove_info_encode(&A.info, info, sizeof info);
  for (int i = 0; i < 5; i++) {
    uint16_t ch[5];
    for (int k = 0; k < 5; k++) ch[k] = (uint16_t)(1000 + 100 * i + 10 * k);
    gp_sample smp = gp_glove_sample((uint16_t)i, (uint32_t)(10000 * i), ch);
    n[i] = gp_glove_sample_encode(&smp, GP_SPEC_HASH, s[i], sizeof s[i]);
  }
  memcpy(two, s[2], n[2]);
  memcpy(two + n[2], s[3], n[3]);
  const struct {
    uint64_t ms;
    const uint8_t *b;
    size_t n;
  } c[] = { { 0, info, ni },   { 10, s[0], n[0] - 1 },       { 30, s[0] + n[0] - 1, 1 },
            { 40, s[1], 10 },  { 50, s[1] + 10, n[1] - 10 }, { 60, two, n[2] + n[3] },
            { 70, s[4], n[4] } };
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++)
    if (mr_rec_writer_add(&w, c[i].ms * 1000000u, c[i].b, c[i].n, &ie) != 0) fail_msg("%s", ie.msg);
  if (mr_rec_writer_close(&w, &ie) != 0) fail_msg("%s", ie.msg);
}

/* A frame is read at the chunk holding its delimiter, even when that chunk
 * is the delimiter alone; the newest SAMPLE at or before a time counts one
 * read at that very time, and of two read at once the later. */
static void a_frame_is_read_at_the_chunk_holding_its_delimiter(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  write_cut_take(tt_path(dir, "cut.mrec"));
  mr_take_rec r;
  mr_take_error err;
  if (mr_take_rec_load(tt_path(dir, "cut.mrec"), &r, &err) != 0) fail_msg("%s", err.msg);
  static const uint64_t ms[] = { 0, 30, 50, 60, 60, 70 };
  static const size_t chunk[] = { 0, 2, 4, 5, 5, 6 };
  assert_int_equal(r.n_frames, 6);
  for (size_t i = 0; i < r.n_frames; i++) {
    assert_int_equal(r.frames[i].t_ns, ms[i] * 1000000u);
    assert_int_equal(r.frames[i].chunk, chunk[i]);
  }
  assert_int_equal(mr_take_rec_sample_at(&r, 29999999u), -1);
  assert_int_equal(mr_take_rec_sample_at(&r, 30000000u), 1);
  assert_int_equal(mr_take_rec_sample_at(&r, 60000000u), 4);
  uint16_t ch[MR_TAKE_CHANNELS] = { 0 };
  assert_int_equal(mr_take_rec_set_sample(&r, 0, ch, &err), -1);
  says(&err, "frame 0 is not a SAMPLE");
  assert_int_equal(mr_take_rec_set_sample(&r, r.n_frames, ch, &err), -1);
  says(&err, "frame 6 is not a SAMPLE");
  mr_take_rec_free(&r);
  tt_rmdir(dir);
  free(dir);
}

/* Trimmed from 45 ms, the take starts on a frame: the chunk at 50 ms holds
 * only the end of sample 1 and is dropped whole, so the INFO leads, then
 * samples 2 and 3 at 15 ms and sample 4 at 25 ms. */
static void a_trim_that_starts_inside_a_frame_drops_its_end(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  write_cut_take(tt_path(dir, "cut.mrec"));
  mr_take_rec r, t;
  mr_take_error err;
  if (mr_take_rec_load(tt_path(dir, "cut.mrec"), &r, &err) != 0) fail_msg("%s", err.msg);
  if (mr_take_trim_rec(&r, 0.045, INFINITY, &t, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(t.n_chunks, 3);
  assert_int_equal(t.chunks[1].t_ns, 15000000u);
  assert_int_equal(t.chunks[2].t_ns, 25000000u);
  assert_int_equal(t.len, r.chunks[0].len + r.chunks[5].len + r.chunks[6].len);
  assert_memory_equal(t.data + t.chunks[1].off, r.data + r.chunks[5].off, r.chunks[5].len);
  assert_int_equal(t.n_frames, 4);
  assert_int_equal(t.frames[1].msg.u.sample.seq, 2);
  mr_take_rec_free(&r);
  mr_take_rec_free(&t);
  tt_rmdir(dir);
  free(dir);
}

/* An offset of 10 ms on the index finger: each SAMPLE takes the index
 * value of the newest read at or before 10 ms earlier (one read exactly
 * then counts), the first SAMPLE's when none is; the middle finger, offset
 * 0, is untouched even where two SAMPLEs are read at once. */
static void an_offset_takes_the_sample_read_exactly_then_and_the_first_before_any(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  write_cut_take(tt_path(dir, "cut.mrec"));
  mr_take_rec r;
  mr_take_error err;
  if (mr_take_rec_load(tt_path(dir, "cut.mrec"), &r, &err) != 0) fail_msg("%s", err.msg);
  const double off[MR_TAKE_CHANNELS] = { 0, 0.01, 0, 0, 0 };
  if (mr_take_offset_rec(&r, off, &err) != 0) fail_msg("%s", err.msg);
  /* Samples read at 30, 50, 60, 60, 70 ms take samples 0, 0, 1, 1, 3. */
  static const int from[] = { 0, 0, 1, 1, 3 };
  for (int s = 0; s < 5; s++) {
    assert_int_equal(r.frames[s + 1].msg.u.sample.ch[1], 1000 + 100 * from[s] + 10);
    assert_int_equal(r.frames[s + 1].msg.u.sample.ch[2], 1000 + 100 * s + 20);
  }
  mr_take_rec_free(&r);
  tt_rmdir(dir);
  free(dir);
}

/* Called on a take directly, the edits refuse what the book refuses: a
 * punch-in not before its punch-out, a min_cutoff of 0; and scaling that
 * would stretch a silence past an hour, while one of exactly an hour is
 * taken. */
static void the_edits_refuse_an_empty_punch_a_zero_cutoff_and_a_silence_past_an_hour(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  write_cut_take(tt_path(dir, "cut.mrec"));
  mr_take_rec r, over;
  mr_take_error err;
  if (mr_take_rec_load(tt_path(dir, "cut.mrec"), &r, &err) != 0 ||
      mr_take_rec_copy(&over, &r, &err) != 0)
    fail_msg("%s", err.msg);
  assert_int_equal(mr_take_punch_rec(&r, &over, 1u, 0.04, 0.04, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "the punch-in time 0.04 s must come before the punch-out time 0.04 s");
  assert_int_equal(mr_take_smooth_rec(&r, 1u, 0.0, 0.0, 1.0, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "got 0, 0, 1");
  mr_take_rec t;
  assert_int_equal(mr_take_trim_rec(&r, -0.5, 1.0, &t, &err), -1);
  says(&err, "the start time must be a time 0..1e6 s, got -0.5");
  mr_take_rec_free(&r);
  mr_take_rec_free(&over);
  /* Two chunks 2400 s apart: by 1.5 the silence is an hour, by 1.6 more. */
  mr_rec_writer w;
  mr_io_error ie;
  const uint8_t byte = 1;
  if (mr_rec_writer_open(&w, tt_path(dir, "gap.mrec"), GP_SPEC_HASH, 0, &ie) != 0 ||
      mr_rec_writer_add(&w, 0, &byte, 1, &ie) != 0 ||
      mr_rec_writer_add(&w, 2400000000000u, &byte, 1, &ie) != 0 ||
      mr_rec_writer_close(&w, &ie) != 0)
    fail_msg("%s", ie.msg);
  if (mr_take_rec_load(tt_path(dir, "gap.mrec"), &r, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(mr_take_scale_rec(&r, 1.6, &err), -1);
  says(&err, "scaled by 1.6, the take would hold a silence over an hour");
  if (mr_take_scale_rec(&r, 1.5, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(r.chunks[1].t_ns, 3600000000000u);
  mr_take_rec_free(&r);
  tt_rmdir(dir);
  free(dir);
}

/* The edges of the book's operations: a take of no known scene is punched
 * into one of a known scene; an armed glove the over take has not changes
 * nothing; a punch-out past 1e6 s, an offset past an hour, a split at 0 or
 * at the take's end and a negative start are refused, each saying what;
 * an offset of exactly an hour is taken. */
static void the_edges_of_punch_split_trim_and_offset(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  B.scene = 0;
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_error err;
  punch(&b, "ab", 2.0, 4.0); /* b's scene is not known */
  char pa[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  const char *two[] = { pa, pa };
  if (mr_take_book_add(&b, "aa", two, 2, false, NULL, &err) != 0) fail_msg("%s", err.msg);
  mr_take_punch_def d = mr_default_take_punch_def();
  d.base = "aa";
  d.over = "b";
  d.name = "aab";
  d.arms[0] = (mr_take_arm){ 1, 1 };
  d.n_arms = 1;
  d.t_in = 1.0;
  d.t_out = 2.0;
  if (mr_take_book_punch(&b, &d, NULL, &err) != 0) fail_msg("%s", err.msg);
  char paths[MR_TAKE_MAX_GLOVES][MR_TAKE_PATH_MAX];
  size_t n, len_a, len;
  if (mr_take_book_paths(&b, "aab", paths, MR_TAKE_MAX_GLOVES, &n, &err) != 0)
    fail_msg("%s", err.msg);
  char *want = file_bytes(pa, &len_a), *got = file_bytes(paths[1], &len);
  assert_int_equal(len, len_a);
  assert_memory_equal(got, want, len);
  free(want);
  free(got);
  d.base = "a";
  d.name = NULL;
  d.arms[0] = (mr_take_arm){ 0, 1 };
  d.t_out = 2e6;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "the punch-out time must be a time 0..1e6 s, got 2e+06");
  d.t_in = -0.5;
  assert_int_equal(mr_take_book_punch(&b, &d, NULL, &err), -1);
  says(&err, "expected 0 <= punch-in < punch-out, got -0.5");
  assert_int_equal(mr_take_book_split(&b, "a", 0.0, NULL, NULL, NULL, &err), -1);
  says(&err, "the split time must be a time > 0 s, got 0");
  assert_int_equal(mr_take_book_split(&b, "a", 6.0, NULL, NULL, NULL, &err), -1);
  says(&err, "take 'a' lasts 6 s: nothing after 6 s");
  assert_int_equal(mr_take_book_trim(&b, "a", -0.5, 1.0, NULL, NULL, &err), -1);
  says(&err, "expected 0 <= from < to, got -0.5 and 1 s");
  double off[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS] = { { 0 } };
  off[0][3] = 3600.0;
  off[0][4] = -3600.0;
  if (mr_take_book_offset(&b, "a", off, "hour", NULL, &err) != 0) fail_msg("%s", err.msg);
  X = A;
  for (size_t i = 0; i < A.n; i++) {
    X.ch[i][3] = A.ch[0][3];
    X.ch[i][4] = A.ch[A.n - 1][4];
  }
  mr_take_rec r;
  load_take(&b, "hour", &r);
  holds(&r, &X);
  mr_take_rec_free(&r);
  off[0][3] = 3600.5;
  assert_int_equal(mr_take_book_offset(&b, "a", off, NULL, NULL, &err), -1);
  says(&err, "an offset must be -3600..3600 s, got 3600.5 for 0:3");
  assert_int_equal(b.n, 6);
  mr_take_book_close(&b);
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* A take's name holds at most 63 bytes and a book's directory at most 447;
 * a take whose first glove was recorded against a scene and second
 * against none is added, as of that scene. */
static void names_at_their_longest_and_a_glove_of_no_scene(void **state) {
  (void)state;
  char *dir = tt_tmpdir();
  make_a();
  make_b();
  B.scene = 0;
  mr_take_book b;
  book_ab(dir, &b);
  mr_take_error err;
  char name[MR_TAKE_NAME_MAX + 1];
  memset(name, 'n', MR_TAKE_NAME_MAX);
  name[MR_TAKE_NAME_MAX] = '\0';
  assert_int_equal(mr_take_book_check_name(&b, name, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_NAME);
  says(&err, "at most 63 bytes");
  name[MR_TAKE_NAME_MAX - 1] = '\0';
  assert_int_equal(mr_take_book_check_name(&b, name, &err), 0);
  char pa[MR_TAKE_PATH_MAX], pb[MR_TAKE_PATH_MAX];
  snprintf(pa, sizeof pa, "%s", tt_path(dir, "a.mrec"));
  snprintf(pb, sizeof pb, "%s", tt_path(dir, "b.mrec"));
  const char *ab[] = { pa, pb };
  if (mr_take_book_add(&b, name, ab, 2, false, NULL, &err) != 0) fail_msg("%s", err.msg);
  assert_true(mr_take_book_find(&b, name)->scene_hash == 0x5ce9e5ce9e000001ull);
  mr_take_book_close(&b);
  char longest[MR_TAKE_PATH_MAX];
  memset(longest, 'd', MR_TAKE_PATH_MAX - 64);
  longest[0] = '/';
  longest[MR_TAKE_PATH_MAX - 64] = '\0';
  assert_int_equal(mr_take_book_open(longest, false, &b, &err), -1);
  assert_int_equal(err.status, MR_TAKE_ERR_ARG);
  says(&err, "expected a book's directory");
  tt_rmdir(tt_path(dir, "book"));
  tt_rmdir(dir);
  free(dir);
}

/* A channel list: gloves 0..7, fingers 0..4 or a finger's whole name, and
 * no more channels than there is room for. */
static void a_channel_list_takes_gloves_0_to_7_and_fingers_by_number_or_whole_name(void **state) {
  (void)state;
  mr_take_arm arms[2];
  size_t n;
  mr_take_error err;
  if (mr_take_arms_parse("7:little,0:4", arms, 2, &n, &err) != 0) fail_msg("%s", err.msg);
  assert_int_equal(n, 2);
  assert_int_equal(arms[0].glove, 7);
  assert_int_equal(arms[0].finger, 4);
  assert_int_equal(arms[1].glove, 0);
  assert_int_equal(arms[1].finger, 4);
  assert_int_equal(mr_take_arms_parse("8:1", arms, 2, &n, &err), -1);
  says(&err, "glove 0..7), got '8:1'");
  assert_int_equal(mr_take_arms_parse("0:5", arms, 2, &n, &err), -1);
  says(&err, "got '5'");
  assert_int_equal(mr_take_arms_parse("0:thu", arms, 2, &n, &err), -1);
  says(&err, "got 'thu'");
  assert_int_equal(mr_take_arms_parse("0:1,0:2,0:3", arms, 2, &n, &err), -1);
  says(&err, "more than 2 channels");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(
        a_punch_in_of_two_channels_from_2_to_4_s_stores_the_expected_merge_byte_for_byte),
    cmocka_unit_test(
        a_punched_channel_lands_at_the_over_takes_calibrated_value_and_nothing_else_moves),
    cmocka_unit_test(a_punch_takes_the_over_sample_read_at_the_same_time),
    cmocka_unit_test(split_and_trim_keep_times_lengths_and_a_leading_info),
    cmocka_unit_test(delete_hides_restore_returns_and_no_take_file_is_ever_rewritten),
    cmocka_unit_test(smoothing_changes_only_the_chosen_channels_as_an_independent_one_euro_does),
    cmocka_unit_test(smoothing_with_no_channels_chosen_filters_every_finger),
    cmocka_unit_test(an_offset_shifts_one_channel_and_leaves_the_others),
    cmocka_unit_test(scaling_multiplies_every_chunk_time_and_keeps_the_bytes),
    cmocka_unit_test(a_malformed_list_or_a_missing_take_file_is_named),
    cmocka_unit_test(a_long_take_list_reads_back_whole),
    cmocka_unit_test(each_field_of_a_take_list_is_checked),
    cmocka_unit_test(a_cut_off_take_is_used_up_to_its_last_whole_chunk_and_says_so),
    cmocka_unit_test(different_scenes_unknown_names_and_absurd_numbers_are_refused),
    cmocka_unit_test(a_take_of_the_most_gloves_is_added_and_one_more_is_refused),
    cmocka_unit_test(a_take_reads_counts_by_the_adc_full_scale_its_info_gives),
    cmocka_unit_test(a_value_goes_back_to_the_nearest_count_within_the_adc_range),
    cmocka_unit_test(an_info_of_another_spec_hash_is_not_a_frame),
    cmocka_unit_test(a_frame_is_read_at_the_chunk_holding_its_delimiter),
    cmocka_unit_test(a_trim_that_starts_inside_a_frame_drops_its_end),
    cmocka_unit_test(an_offset_takes_the_sample_read_exactly_then_and_the_first_before_any),
    cmocka_unit_test(the_edits_refuse_an_empty_punch_a_zero_cutoff_and_a_silence_past_an_hour),
    cmocka_unit_test(the_edges_of_punch_split_trim_and_offset),
    cmocka_unit_test(names_at_their_longest_and_a_glove_of_no_scene),
    cmocka_unit_test(a_channel_list_takes_gloves_0_to_7_and_fingers_by_number_or_whole_name),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
