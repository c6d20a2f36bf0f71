/* What the take room's tests share (take_rig.c). */
#ifndef TEST_TAKE_RIG_H
#define TEST_TAKE_RIG_H

#include <stddef.h>

#include "mr_take.h"
#include "take_gen.h"

/* Big: kept off the stack. A and B as make_a and make_b leave them; X for
 * a test's own. */
extern gen_take A, B, X;

/* Take A: 6 s at 100 Hz, calibrated 200..3800, INFO again at 3 s. */
void make_a(void);
/* Take B: the same glove calibrated 100..4000, sampled 5 ms off A's. */
void make_b(void);

/* The file's bytes (free them); fails the test when it cannot be read. */
char *file_bytes(const char *path, size_t *len);
/* The one file of take `name` in b, into out (MR_TAKE_PATH_MAX). */
void take_path(const mr_take_book *b, const char *name, char *out);
/* A book in dir holding A and B as takes "a" and "b". */
void book_ab(const char *dir, mr_take_book *b);
/* A and B made afresh, and a book of them in a new temporary folder,
 * returned (book_done removes it). */
char *book_ab_tmp(mr_take_book *b);
/* Closes b and removes the folder book_ab_tmp made, and its book. */
void book_done(mr_take_book *b, char *dir);
/* Fingers 1 and 2 of B punched into A over [t_in, t_out), as take name. */
void punch(mr_take_book *b, const char *name, double t_in, double t_out);
/* Take `name` of b, read. */
void load_take(const mr_take_book *b, const char *name, mr_take_rec *r);
/* The SAMPLEs of r's frames, in order, must hold want's channels. */
void holds(const mr_take_rec *r, const gen_take *want);

void write_text(const char *path, const char *text);
/* err's message must contain what. */
void says(const mr_take_error *err, const char *what);

#endif
