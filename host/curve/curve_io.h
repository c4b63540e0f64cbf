/* Reading and writing curve files: VECT (Geomview/plCurve, with plCurve's
 * constraint comments), TSV (x y z per line, blank line between components,
 * all closed) and plain KnotPlot "x y z" lists (one closed component).
 *
 * Readers report malformed input as one line "FILE:LINE: what is wrong" in
 * err with status TR_EPARSE. Writers print %.17g, so write -> read is exact,
 * and write to a temporary name in the same directory, fsync and rename, so a
 * failed or interrupted write never leaves a half-written file. */
#ifndef TR_CURVE_IO_H
#define TR_CURVE_IO_H

#include "curve/curve.h"
#include "util/text_file.h" /* tr_write_file_atomic, used by every writer */

typedef enum tr_format {
    TR_FORMAT_AUTO = 0, /* by extension (.vect, .tsv, .txt/.dat/.knot) and then by content */
    TR_FORMAT_VECT,
    TR_FORMAT_TSV,
    TR_FORMAT_KNOTPLOT
} tr_format;

/* Parses a whole file held in memory; name is used in messages. */
int tr_curve_parse(const char *name, const char *text, size_t len, tr_format fmt, tr_curve *out,
                   tr_error *err);

int tr_curve_read(const char *path, tr_format fmt, tr_curve *out, tr_error *err);

/* comments: optional lines written as "# ..." at the top (certificates:
 * N, length, ropelength, the command line, ...); may be NULL. */
int tr_curve_write(const char *path, tr_format fmt, const tr_curve *c, const char *comments,
                   tr_error *err);

/* Checks, writing nothing, that tr_curve_write(path, fmt, c, ...) would get
 * past everything but the coordinates: the format is known, can hold c's
 * components, openness and constraints, and path is writable. For commands
 * that write their result after a long run. */
int tr_curve_check_output(const char *path, tr_format fmt, const tr_curve *c, tr_error *err);

/* Formats the curve as the text tr_curve_write would write, into a buffer
 * the caller frees; fmt must not be TR_FORMAT_AUTO. TR_EINVAL if the format
 * cannot hold the curve (open components or constraints in TSV/KnotPlot,
 * several components in a KnotPlot list, non-finite coordinates). */
int tr_curve_format(const tr_curve *c, tr_format fmt, const char *comments, char **text, size_t *len,
                    tr_error *err);

tr_format tr_format_from_name(const char *name);

#endif
