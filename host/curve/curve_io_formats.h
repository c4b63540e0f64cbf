/* This file contains what the curve file formats share inside curve/ (not
 * part of the public API, which is curve_io.h): the lexing and validation
 * helpers in curve_io.c and each format's reader and writer (vect.c,
 * point_list.c), which curve_io.c dispatches to. */
#ifndef TR_CURVE_IO_FORMATS_H
#define TR_CURVE_IO_FORMATS_H

#include <stddef.h>

#include "curve/curve.h"
#include "util/error.h"
#include "util/text_file.h"

/* --- shared helpers (curve_io.c) */

/* Whether c is a blank (space, tab, CR, VT, FF, newline). */
int tr_curve_io_is_space(char c);
/* Copies a token into buf for a message: at most 24 characters, anything
 * unprintable shown as '?', so an error stays one readable line. */
const char *tr_curve_io_quote(char *buf, size_t bufn, const char *p, size_t n);
/* Parses a whole token as a finite decimal double: 0 ok, 1 not a number,
 * 2 not finite. */
int tr_curve_io_token_double(const char *p, size_t n, double *out);
/* The same, with what a token of more than 17 significant digits holds
 * beyond *hi in *lo (read as a long double; 0 for a shorter token). */
int tr_curve_io_token_split(const char *p, size_t n, double *hi, double *lo);
/* Fails with TR_EPARSE as "NAME:LINE: what". */
int tr_curve_io_parse_fail(tr_error *err, const char *name, size_t line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* Refuses coincident consecutive vertices; vline[i] is vertex i's line. */
int tr_curve_io_check_edges(const tr_curve *c, const size_t *vline, const char *name, tr_error *err);
/* Refuses a component too short for its kind (closed >= 3, open >= 2). */
int tr_curve_io_check_size(int closed, size_t n, int k, size_t line, const char *name, tr_error *err);
/* Words of p[0..n), split on blanks: up to maxw of them in w/wn; returns
 * how many there are. */
size_t tr_curve_io_split_words(const char *p, size_t n, const char **w, size_t *wn, size_t maxw);
/* Each line of comments becomes "# line". */
void tr_curve_io_comments(tr_text *b, const char *comments);

/* --- VECT (vect.c) */

/* Whether text starts (after comments) with the word VECT. */
int tr_vect_sniff(const char *name, const char *text, size_t len);
int tr_vect_parse(const char *name, const char *text, size_t len, tr_curve *out, tr_error *err);
void tr_vect_format(tr_text *b, const tr_curve *c, const char *comments);
/* Vertex i's three coordinates, sep between them: each to 17 digits, or
 * to 21 where it has a low part (curve.h). */
void tr_curve_io_vertex(tr_text *b, const tr_curve *c, size_t i, const char *sep);

/* --- TSV and KnotPlot lists (point_list.c) */

/* multi: blank lines end a component (TSV), else one component (KnotPlot). */
int tr_point_list_parse(const char *name, const char *text, size_t len, int multi, tr_curve *out,
                        tr_error *err);
void tr_point_list_format(tr_text *b, const tr_curve *c, const char *comments);

#endif
