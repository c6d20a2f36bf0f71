/* `marionette take SUBCOMMAND BOOK ...`: the take list on the command line,
 * for scripts. Every operation is mr_take's (host/take/README.md); this
 * file parses arguments and prints. It maps no graphics library. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "mr_take.h"

typedef struct sub {
  const char *name, *synopsis, *what;
  const char *options;  /* the options it takes, space separated, each with a space after */
  int min_pos, max_pos; /* positional arguments after BOOK */
} sub;

static const sub SUBS[] = {
  { "list", "list BOOK [--all]", "the takes: name, duration, gloves, how each was made", "--all ",
    0, 0 },
  { "add", "add BOOK FILE.mrec... [--name NAME] [--move]",
    "a recorded take, one .mrec per glove in glove order (makes the book)", "--name --move ", 1,
    MR_TAKE_MAX_GLOVES },
  { "punch", "punch BOOK BASE OVER --arm G:F[,G:F...] --in S --out S [--name NAME]",
    "a new take: BASE, the armed channels from OVER between --in and --out",
    "--arm --in --out --name ", 2, 2 },
  { "split", "split BOOK NAME --at S [--name FIRST] [--name2 SECOND]",
    "two new takes, before S and from S on; the second's times start at 0", "--at --name --name2 ",
    1, 1 },
  { "trim", "trim BOOK NAME --from S --to S [--name NAME]",
    "a new take of [from, to), its times starting at 0", "--from --to --name ", 1, 1 },
  { "delete", "delete BOOK NAME", "hide a take from the list; its files stay (see restore)", "", 1,
    1 },
  { "restore", "restore BOOK NAME", "bring a deleted take back", "", 1, 1 },
  { "rename", "rename BOOK NAME NEW", "rename a take in the list; its files stay", "", 2, 2 },
  { "smooth", "smooth BOOK NAME [--channels G:F,...] [FILTER OPTIONS] [--name NAME]",
    "a new take, the channels (default all) through a One Euro filter",
    "--min-cutoff --beta --d-cutoff --channels --name ", 1, 1 },
  { "offset", "offset BOOK NAME --channel G:F=S [--channel ...] [--name NAME]",
    "a new take, each channel given played S s later (S < 0: earlier)", "--channel --name ", 1, 1 },
  { "scale", "scale BOOK NAME --factor F [--name NAME]",
    "a new take, its times multiplied by F > 0: 2 plays it at half speed", "--factor --name ", 1,
    1 },
  { "show", "show BOOK NAME", "a take and its lineage, back to its recorded takes", "", 1, 1 },
};
enum { N_SUBS = sizeof SUBS / sizeof SUBS[0], MAX_POS = MR_TAKE_MAX_GLOVES + 2 };

void mr_cmd_take_usage(void) {
  printf("usage: marionette take SUBCOMMAND BOOK [ARGS]\n\n"
         "A take list (BOOK): a directory holding takes.json and the takes' files.\n"
         "Takes are never rewritten: every operation makes a new take that names its\n"
         "source, and delete only hides one. Times are seconds of show time. New takes\n"
         "are named --name, else the first free take-N. Elsewhere, BOOK:NAME names a\n"
         "take wherever a .mrec is taken (run --replay, render --take, export).\n"
         "A channel G:F is glove G, counted from 0 in the take's glove order (the\n"
         "display's glove 1 is 0), and finger F: 0..4 or thumb, index, middle, ring,\n"
         "little. Takes are recorded and punched in with marionette run --takes.\n\n"
         "subcommands:\n");
  for (int i = 0; i < N_SUBS; i++) printf("  %s\n      %s\n", SUBS[i].synopsis, SUBS[i].what);
  printf("\noptions (each subcommand takes those its line shows):\n"
         "  --all               list: deleted takes too\n"
         "  --name NAME         the new take's name (split: the first part's)\n"
         "  --name2 NAME        split: the second part's name\n"
         "  --move              add: move the files in (removing them) instead of copying\n"
         "  --arm G:F[,G:F...]  punch: the armed channels\n"
         "  --in S, --out S     punch: the punch-in and punch-out times\n"
         "  --at S              split: where to cut\n"
         "  --from S, --to S    trim: what to keep, [from, to)\n"
         "  --min-cutoff HZ     smooth's FILTER OPTIONS: the One Euro filter's minimum\n"
         "                      cutoff (default 1; lower: smoother, with more lag),\n"
         "  --beta B            its speed coefficient (default 0; more: less lag in\n"
         "                      fast moves),\n"
         "  --d-cutoff HZ       its derivative's cutoff (default 1)\n"
         "  --channels G:F,...  smooth: the channels to smooth (default all)\n"
         "  --channel G:F=S     offset: a channel and its delay in s; repeat for more\n"
         "  --factor F          scale: the time factor, > 0 (over 1: longer and slower)\n"
         "  -h, --help          this help; after a subcommand, its own\n"
         "\nSee marionette(1), \"take\".\n");
}

static int usage_error(const char *fmt, const char *a, const char *b) {
  fprintf(stderr, "marionette take: ");
  fprintf(stderr, fmt, a, b);
  fprintf(stderr, " (see marionette take --help)\n");
  return MR_EXIT_USAGE;
}

typedef struct opts {
  const sub *sub;
  const char *book, *pos[MAX_POS];
  int n_pos;
  const char *name, *name2, *arm, *channels;
  double in, out, at, from, to, factor, min_cutoff, beta, d_cutoff;
  bool move, all;
  double offset[MR_TAKE_MAX_GLOVES][MR_TAKE_CHANNELS];
  int n_offsets;
} opts;

static int number(const char *opt, const char *v, double *out) {
  char *end;
  double d = strtod(v, &end);
  if (end == v || *end != '\0' || !isfinite(d))
    return usage_error("%s expects a number, got '%s'", opt, v), -1;
  *out = d;
  return 0;
}

/* --channel G:F=S */
static int channel_offset(opts *o, const char *v) {
  char arm[32];
  const char *eq = strchr(v, '=');
  if (eq == NULL || (size_t)(eq - v) >= sizeof arm)
    return usage_error("--channel expects GLOVE:FINGER=SECONDS, got '%s'%s", v, ""), -1;
  memcpy(arm, v, (size_t)(eq - v));
  arm[eq - v] = '\0';
  mr_take_arm a;
  size_t n;
  mr_take_error err;
  if (mr_take_arms_parse(arm, &a, 1, &n, &err) != 0)
    return usage_error("--channel: %s%s", err.msg, ""), -1;
  if (number("--channel", eq + 1, &o->offset[a.glove][a.finger]) != 0) return -1;
  o->n_offsets++;
  return 0;
}

static int valued(opts *o, const char *opt, const char *v) {
  struct {
    const char *name;
    double *d;
    const char **s;
  } t[] = { { "--in", &o->in, NULL },
            { "--out", &o->out, NULL },
            { "--at", &o->at, NULL },
            { "--from", &o->from, NULL },
            { "--to", &o->to, NULL },
            { "--factor", &o->factor, NULL },
            { "--beta", &o->beta, NULL },
            { "--min-cutoff", &o->min_cutoff, NULL },
            { "--d-cutoff", &o->d_cutoff, NULL },
            { "--name", NULL, &o->name },
            { "--name2", NULL, &o->name2 },
            { "--arm", NULL, &o->arm },
            { "--channels", NULL, &o->channels } };
  if (strcmp(opt, "--channel") == 0) return channel_offset(o, v);
  for (size_t i = 0; i < sizeof t / sizeof t[0]; i++) {
    if (strcmp(opt, t[i].name) != 0) continue;
    if (t[i].s != NULL) *t[i].s = v;
    return t[i].d != NULL ? number(opt, v, t[i].d) : 0;
  }
  return usage_error("unknown option '%s'%s", opt, "");
}

/* True if sub s takes option opt. */
static bool takes(const sub *s, const char *opt) {
  char key[40];
  snprintf(key, sizeof key, "%s ", opt);
  return strlen(opt) < 30 && strstr(s->options, key) != NULL;
}

/* 0, 1 for --help (printed), or MR_EXIT_USAGE. */
static int parse(opts *o, int argc, char **argv) {
  for (int i = 2; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      printf("usage: marionette take %s\n\n%s\n", o->sub->synopsis, o->sub->what);
      return 1;
    }
    if (strncmp(a, "--", 2) != 0 || a[2] == '\0') {
      if (o->book == NULL)
        o->book = a;
      else if (o->n_pos < MAX_POS)
        o->pos[o->n_pos++] = a;
      else
        return usage_error("too many arguments, from '%s'%s", a, "");
      continue;
    }
    if (!takes(o->sub, a))
      return usage_error("take %s does not take the option '%s'", o->sub->name, a);
    if (strcmp(a, "--all") == 0 || strcmp(a, "--move") == 0) {
      *(a[2] == 'a' ? &o->all : &o->move) = true;
      continue;
    }
    if (i + 1 >= argc) return usage_error("%s expects a value%s", a, "");
    if (valued(o, a, argv[++i]) != 0) return MR_EXIT_USAGE;
  }
  if (o->book == NULL) return usage_error("take %s expects a BOOK directory%s", o->sub->name, "");
  if (o->n_pos < o->sub->min_pos || o->n_pos > o->sub->max_pos)
    return usage_error("usage: marionette take %s%s", o->sub->synopsis, "");
  return 0;
}

static const char *const FINGERS[] = { "thumb", "index", "middle", "ring", "little" };

/* The name of the take with id, or "#id" when the list has none. */
static const char *name_of(const mr_take_book *b, int id, char *buf, size_t size) {
  const mr_take_entry *e = mr_take_book_find_id(b, id);
  if (e != NULL) return e->name;
  snprintf(buf, size, "#%d", id);
  return buf;
}

static void print_arms(const mr_take_entry *e, bool offsets) {
  for (size_t i = 0; i < e->n_arms; i++) {
    const mr_take_arm *a = &e->arms[i];
    printf("%s%d:%s", i ? "," : "", a->glove, FINGERS[a->finger]);
    if (offsets) printf("=%g", e->offset[a->glove][a->finger]);
  }
}

/* How e was made, on one line without its end. */
static void print_made(const mr_take_book *b, const mr_take_entry *e) {
  char s1[16], s2[16];
  const char *src = name_of(b, e->source_id, s1, sizeof s1);
  switch (e->how) {
  case MR_TAKE_RECORDED:
    printf("recorded");
    break;
  case MR_TAKE_PUNCHED:
    printf("punch of %s by %s on ", src, name_of(b, e->over_id, s2, sizeof s2));
    print_arms(e, false);
    printf(" from %g to %g s", e->t0, e->t1);
    break;
  case MR_TAKE_SPLIT:
    printf("split of %s at %g s, %s part", src, e->t0, e->part == 1 ? "first" : "second");
    break;
  case MR_TAKE_TRIMMED:
    printf("trim of %s to [%g, %g) s", src, e->t0, e->t1);
    break;
  case MR_TAKE_SMOOTHED:
    printf("smooth of %s, min-cutoff %g Hz, beta %g, d-cutoff %g Hz, on ", src, e->min_cutoff,
           e->beta, e->d_cutoff);
    if (e->n_arms == 0) printf("every channel");
    print_arms(e, false);
    break;
  case MR_TAKE_OFFSET:
    printf("offset of %s: ", src);
    print_arms(e, true);
    break;
  case MR_TAKE_SCALED:
    printf("scale of %s by %g", src, e->factor);
    break;
  }
}

static void print_entry(const mr_take_book *b, const mr_take_entry *e) {
  printf("%-16s %9.3f s  %zu glove%s  ", e->name, e->duration, e->n_files,
         e->n_files == 1 ? " " : "s");
  print_made(b, e);
  printf("%s\n", e->deleted ? "  (deleted)" : "");
}

static int run_list(mr_take_book *b, const opts *o) {
  size_t shown = 0;
  for (size_t i = 0; i < b->n; i++) {
    if (b->takes[i].deleted && !o->all) continue;
    print_entry(b, &b->takes[i]);
    shown++;
  }
  if (shown == 0) printf("no takes in %s\n", b->dir);
  return MR_EXIT_OK;
}

/* The take and, indented, every take it was made from. */
static void print_lineage(const mr_take_book *b, const mr_take_entry *e, int depth) {
  printf("%*s", 2 * depth, "");
  print_entry(b, e);
  if (depth > 64) return;
  const mr_take_entry *s = e->source_id ? mr_take_book_find_id(b, e->source_id) : NULL;
  const mr_take_entry *v = e->over_id ? mr_take_book_find_id(b, e->over_id) : NULL;
  if (s != NULL) print_lineage(b, s, depth + 1);
  if (v != NULL) print_lineage(b, v, depth + 1);
}

static int run_show(mr_take_book *b, const opts *o, mr_take_error *err) {
  const mr_take_entry *e = mr_take_book_find(b, o->pos[0]);
  if (e == NULL) {
    snprintf(err->msg, sizeof err->msg, "%s: no take named '%s'", b->dir, o->pos[0]);
    return -1;
  }
  print_lineage(b, e, 0);
  printf("files:");
  for (size_t k = 0; k < e->n_files; k++) printf(" %s/%s", b->dir, e->files[k]);
  printf("\nscene hash %016llx\n", (unsigned long long)e->scene_hash);
  return 0;
}

static int need(double v, const char *opt, const opts *o) {
  if (!isnan(v)) return 0;
  return usage_error("take %s expects %s", o->sub->name, opt), -1;
}

static int run_punch(mr_take_book *b, const opts *o, mr_take_made *m, mr_take_error *err) {
  mr_take_punch_def d = mr_default_take_punch_def();
  if (o->arm == NULL) return usage_error("take punch expects --arm G:F[,G:F...]%s", "", "");
  if (need(o->in, "--in", o) || need(o->out, "--out", o)) return MR_EXIT_USAGE;
  if (mr_take_arms_parse(o->arm, d.arms, MR_TAKE_MAX_ARMS, &d.n_arms, err) != 0)
    return usage_error("--arm: %s%s", err->msg, "");
  d.base = o->pos[0];
  d.over = o->pos[1];
  d.name = o->name;
  d.t_in = o->in;
  d.t_out = o->out;
  return mr_take_book_punch(b, &d, m, err);
}

static int run_smooth(mr_take_book *b, const opts *o, mr_take_made *m, mr_take_error *err) {
  mr_take_smooth_def d = mr_default_take_smooth_def();
  if (!isnan(o->min_cutoff)) d.min_cutoff = o->min_cutoff;
  if (!isnan(o->beta)) d.beta = o->beta;
  if (!isnan(o->d_cutoff)) d.d_cutoff = o->d_cutoff;
  if (o->channels != NULL &&
      mr_take_arms_parse(o->channels, d.channels, MR_TAKE_MAX_ARMS, &d.n_channels, err) != 0)
    return usage_error("--channels: %s%s", err->msg, "");
  return mr_take_book_smooth(b, o->pos[0], &d, o->name, m, err);
}

/* The operations that make takes; -1 with err, or MR_EXIT_USAGE. */
static int run_make(mr_take_book *b, const opts *o, mr_take_made *m, mr_take_error *err) {
  const char *s = o->sub->name, *src = o->pos[0];
  if (strcmp(s, "add") == 0)
    return mr_take_book_add(b, o->name, (const char *const *)o->pos, (size_t)o->n_pos, o->move, m,
                            err);
  if (strcmp(s, "punch") == 0) return run_punch(b, o, m, err);
  if (strcmp(s, "smooth") == 0) return run_smooth(b, o, m, err);
  if (strcmp(s, "split") == 0)
    return need(o->at, "--at", o) ? MR_EXIT_USAGE
                                  : mr_take_book_split(b, src, o->at, o->name, o->name2, m, err);
  if (strcmp(s, "trim") == 0)
    return need(o->from, "--from", o) || need(o->to, "--to", o)
               ? MR_EXIT_USAGE
               : mr_take_book_trim(b, src, o->from, o->to, o->name, m, err);
  if (strcmp(s, "scale") == 0)
    return need(o->factor, "--factor", o) ? MR_EXIT_USAGE
                                          : mr_take_book_scale(b, src, o->factor, o->name, m, err);
  if (o->n_offsets == 0) return usage_error("take offset expects --channel G:F=S%s", "", "");
  return mr_take_book_offset(b, src, o->offset, o->name, m, err);
}

/* Runs o on the open book: MR_EXIT_OK, MR_EXIT_USAGE, or -1 with err. */
static int run(mr_take_book *b, const opts *o, mr_take_error *err) {
  const char *s = o->sub->name;
  if (strcmp(s, "list") == 0) return run_list(b, o);
  if (strcmp(s, "show") == 0) return run_show(b, o, err);
  if (strcmp(s, "delete") == 0) return mr_take_book_delete(b, o->pos[0], err);
  if (strcmp(s, "restore") == 0) return mr_take_book_restore(b, o->pos[0], err);
  if (strcmp(s, "rename") == 0) return mr_take_book_rename(b, o->pos[0], o->pos[1], err);
  mr_take_made m;
  memset(&m, 0, sizeof m);
  int rc = run_make(b, o, &m, err);
  if (m.note[0] != '\0') fprintf(stderr, "marionette take: note: %s\n", m.note);
  if (rc != 0) return rc;
  printf("made %s%s%s\n", m.name, m.name2[0] ? " and " : "", m.name2);
  return MR_EXIT_OK;
}

int mr_cmd_take(int argc, char **argv) {
  if (argc < 2)
    return usage_error("expected a subcommand: list, add, punch, split, trim, "
                       "delete, restore, rename, smooth, offset, scale or show%s",
                       "", "");
  if (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0) {
    mr_cmd_take_usage();
    return MR_EXIT_OK;
  }
  opts o;
  memset(&o, 0, sizeof o);
  o.in = o.out = o.at = o.from = o.to = o.factor = NAN;
  o.min_cutoff = o.beta = o.d_cutoff = NAN;
  for (int i = 0; i < N_SUBS; i++)
    if (strcmp(argv[1], SUBS[i].name) == 0) o.sub = &SUBS[i];
  if (o.sub == NULL) return usage_error("unknown subcommand '%s'%s", argv[1], "");
  int p = parse(&o, argc, argv);
  if (p != 0) return p == 1 ? MR_EXIT_OK : p;
  mr_take_book b;
  mr_take_error err;
  if (mr_take_book_open(o.book, strcmp(o.sub->name, "add") == 0, &b, &err) != 0) {
    fprintf(stderr, "marionette take: %s\n", err.msg);
    return MR_EXIT_FAIL;
  }
  int rc = run(&b, &o, &err);
  mr_take_book_close(&b);
  if (rc < 0) fprintf(stderr, "marionette take: %s\n", err.msg);
  return rc < 0 ? MR_EXIT_FAIL : rc;
}
