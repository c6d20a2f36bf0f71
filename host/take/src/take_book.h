/* takes.json's reader and writer (take_json.c), for the book (take_book.c). */
#ifndef TAKE_BOOK_H
#define TAKE_BOOK_H

#include "mr_take.h"

/* Fills b's entries and next_id from text, the contents of path. */
int mr_take_json_read(mr_take_book *b, const char *path, const char *text, mr_take_error *err);
/* Writes b's list to b->dir/takes.json atomically (a temporary, renamed). */
int mr_take_json_write(const mr_take_book *b, mr_take_error *err);

/* The take's entry, visible or not; NULL and an error naming it if none. */
const mr_take_entry *mr_take_book_get(const mr_take_book *b, const char *name, mr_take_error *err);
/* A new entry at the end of the list (not saved), named name or the first
 * free take-N, with a fresh id and its file names; NULL on error. */
mr_take_entry *mr_take_book_append(mr_take_book *b, const char *name, size_t n_files,
                                   mr_take_how how, mr_take_error *err);
/* Removes the newest entry and whatever of its files exist. */
void mr_take_book_drop_last(mr_take_book *b);
/* Reads every file whole: the longest duration, and the one scene hash
 * they share (0: none known); a cut-off file's note goes into note. */
int mr_take_survey(const char *const *paths, size_t n, double *duration, uint64_t *scene,
                   char *note, size_t note_size, mr_take_error *err);

#endif
