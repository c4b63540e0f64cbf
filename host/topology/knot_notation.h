/* Knot notation a user writes down (issue 47): braid words and PD codes,
 * read from text and checked before anything is built from them.
 *
 * Both are lists of integers; the brackets and separators around them are
 * free ("1,1,-2", "[1, 1, -2]", "1 1 -2"; "[[1,5,2,4],[3,1,4,6],[5,3,6,2]]",
 * "X[1,5,2,4] X[3,1,4,6] ...", KnotInfo's and KnotTheory's forms), but every
 * character must be a digit, a sign, a bracket, a comma, a semicolon, white
 * space or (in a PD code) the X of KnotTheory's X[...], so that a typo is an error, not a
 * different knot. */
#ifndef TR_KNOT_NOTATION_H
#define TR_KNOT_NOTATION_H

#include "util/error.h"

/* The most crossings a braid word or PD code may have: far above any table
 * knot (12 crossings, braid words of 75 letters) and what a start curve of
 * a few thousand vertices can hold. */
#define TR_NOTATION_MAX_CROSSINGS 400

/* A braid word: generators sigma_1 .. sigma_{strands-1}; word[k] = +i for
 * sigma_i, -i for its inverse. strands = the largest |i| + 1. */
typedef struct tr_braid {
    int strands;
    int len;
    int *word;
} tr_braid;

/* Reads a braid word. TR_EINVAL with one line for: no generator at all (an
 * empty braid), a generator 0 (generators start at 1), a character that
 * belongs to no braid word, more than TR_NOTATION_MAX_CROSSINGS letters.
 * b is zeroed first; free with tr_braid_free. */
int tr_braid_parse(const char *text, tr_braid *b, tr_error *err);
void tr_braid_free(tr_braid *b);

/* The closure's components: the cycles of the braid's permutation. comp_of
 * (may be NULL) receives, for each strand position 0..strands-1 at the
 * braid's start, its component 0..k-1 (numbered by smallest position).
 * Returns the number of components. */
int tr_braid_components(const tr_braid *b, int *comp_of);

/* A PD code: n crossings X[a, b, c, d] (edge labels 1..2n, a the incoming
 * under edge, counterclockwise; KnotTheory's and KnotInfo's convention). */
typedef struct tr_pd {
    int n;
    int (*x)[4];
} tr_pd;

/* Reads a PD code and checks that it is a diagram: a multiple of 4 numbers,
 * labels in 1..2n, each exactly twice, no crossing whose under strand does
 * not run a -> a+1 (mod 2n, the orientation along the labels) or whose over
 * strand's edges are not consecutive labels, and one component. TR_EINVAL
 * with the first fault, naming the crossing or label. p is zeroed first;
 * free with tr_pd_free. */
int tr_pd_parse(const char *text, tr_pd *p, tr_error *err);
void tr_pd_free(tr_pd *p);

#endif
