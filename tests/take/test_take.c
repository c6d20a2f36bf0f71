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
#include "take_rig.h"

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
  mr_take_book b;
  char *dir = book_ab_tmp(&b);
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
  book_done(&b, dir);
}

/* B's values land in A at the value B's calibration gave them (within one
 * count of A's), and outside the window or the armed channels A's bytes
 * are A's: the frames before 2 s and after 4 s match A's file exactly. */
static void
a_punched_channel_lands_at_the_over_takes_calibrated_value_and_nothing_else_moves(void **state) {
  (void)state;
  mr_take_book b;
  char *dir = book_ab_tmp(&b);
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
  book_done(&b, dir);
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
  book_done(&b, dir);
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
  book_done(&b, dir);
}

/* Delete hides a take (its files stay, it still resolves), restore brings
 * it back, rename moves only the name; across punch, split, trim, smooth,
 * offset, scale, delete, restore and rename no take's file is rewritten. */
static void delete_hides_restore_returns_and_no_take_file_is_ever_rewritten(void **state) {
  (void)state;
  mr_take_book b;
  char *dir = book_ab_tmp(&b);
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

/* Take "sm" of b must hold A with the fingers in mask filtered as the
 * filter above does with fmin, beta and fd, and the others as they were.
 * Returns how many counts the filter changed. */
static int smoothed_holds(const mr_take_book *b, unsigned mask, double fmin, double beta,
                          double fd) {
  X = A;
  int changed = 0;
  for (int k = 0; k < 5; k++) {
    if (!(mask & 1u << k)) continue;
    euro e = { 0 };
    for (size_t i = 0; i < A.n; i++) {
      double v =
          euro_step(&e, gen_value(&A, k, A.ch[i][k]), (double)A.read_ns[i] / 1e9, fmin, beta, fd);
      X.ch[i][k] = gen_raw(&A, k, v);
      changed += X.ch[i][k] != A.ch[i][k];
    }
  }
  mr_take_rec r;
  load_take(b, "sm", &r);
  holds(&r, &X);
  mr_take_rec_free(&r);
  return changed;
}

/* Smoothing with min_cutoff 2.5 Hz, beta 0.3, d_cutoff 1.7 Hz on the
 * index and ring fingers gives what the filter computed here gives, and
 * leaves the other fingers' counts as they were. */
static void
smoothing_changes_only_the_chosen_channels_as_an_independent_one_euro_does(void **state) {
  (void)state;
  mr_take_book b;
  char *dir = book_ab_tmp(&b);
  mr_take_smooth_def d = mr_default_take_smooth_def();
  d.min_cutoff = 2.5;
  d.beta = 0.3;
  d.d_cutoff = 1.7;
  mr_take_error err;
  if (mr_take_arms_parse("0:index,0:3", d.channels, MR_TAKE_MAX_ARMS, &d.n_channels, &err) != 0)
    fail_msg("%s", err.msg);
  if (mr_take_book_smooth(&b, "a", &d, "sm", NULL, &err) != 0) fail_msg("%s", err.msg);
  assert_true(smoothed_holds(&b, 1u << 1 | 1u << 3, 2.5, 0.3, 1.7) > 100);
  book_done(&b, dir);
}

/* With no channels chosen, smoothing filters all five fingers, each by
 * the default filter (min_cutoff 1 Hz, beta 0, d_cutoff 1 Hz). */
static void smoothing_with_no_channels_chosen_filters_every_finger(void **state) {
  (void)state;
  mr_take_book b;
  char *dir = book_ab_tmp(&b);
  mr_take_smooth_def d = mr_default_take_smooth_def();
  mr_take_error err;
  if (mr_take_book_smooth(&b, "a", &d, "sm", NULL, &err) != 0) fail_msg("%s", err.msg);
  assert_true(smoothed_holds(&b, 0x1fu, 1.0, 0.0, 1.0) > 100);
  book_done(&b, dir);
}

/* An offset of -0.137 s on the middle finger: at t it holds A's value at
 * t + 0.137 s (the last sample's at the end); the other fingers stay. */
static void an_offset_shifts_one_channel_and_leaves_the_others(void **state) {
  (void)state;
  mr_take_book b;
  char *dir = book_ab_tmp(&b);
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
  book_done(&b, dir);
}

/* Scaling by 0.25 multiplies every chunk time and rounds to the ns. */
static void scaling_multiplies_every_chunk_time_and_keeps_the_bytes(void **state) {
  (void)state;
  mr_take_book b;
  char *dir = book_ab_tmp(&b);
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
  book_done(&b, dir);
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
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
