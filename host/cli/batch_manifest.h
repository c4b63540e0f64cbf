/* What `tightrope batch` tightens: the knots of a manifest or of a folder of
 * curve files, in their order, each with its start (a file, or a knot or
 * link of the embedded table by name), its N and the tighten options of
 * its own. Reading checks everything a run of hours would otherwise fail
 * on late (a missing start, an unknown name, a bad N, a duplicate name, an
 * option batch sets itself) and names the manifest's FILE:LINE. */
#ifndef TR_BATCH_MANIFEST_H
#define TR_BATCH_MANIFEST_H

#include <stddef.h>

#include "util/error.h"

/* Longest knot name: it names the knot's files in the output folder. */
#define TR_BATCH_NAME_MAX 200

/* Where a knot's start comes from. */
typedef enum tr_batch_start_kind {
    TR_BATCH_FROM_FILE = 0, /* a curve file */
    TR_BATCH_FROM_KNOT,     /* `knot NAME`: KnotInfo's knot, made as `tightrope make knot NAME` makes it */
    TR_BATCH_FROM_LINK      /* `link NAME`: LinkInfo's link, as `tightrope make link NAME` */
} tr_batch_start_kind;

typedef struct tr_batch_knot {
    char *name;  /* [A-Za-z0-9._+-], not starting with '.' or '-'; unique */
    /* the start curve; a manifest's relative paths are taken from its
     * folder. A start by name is made by the batch into OUT/starts/NAME.vect
     * (tr_batch_place_named), a file of its own */
    char *file;
    tr_batch_start_kind from;
    /* a start by name: "knot:3_1", "link:L2a1{0}" (the table's own name,
     * whatever spelling the manifest used); NULL for a file */
    char *source;
    /* a start by name: the notation it is made from ("braid 1,1,1" on its
     * strands), which with source is its identity (tr_batch_knot_start_id) */
    char *notation;
    long n;      /* vertices per component of the tight curve; 0: as the options say */
    char **opts; /* tighten options of this knot, nopts of them */
    int nopts;
    int line;    /* its manifest line; 0 for a folder's file */
} tr_batch_knot;

typedef struct tr_batch_list {
    tr_batch_knot *knots;
    size_t count;
} tr_batch_list;

/* Reads a manifest or, when src is a folder, lists its curve files (.vect,
 * .tsv, .txt, .dat, .knot) in name order, each knot named by its file's
 * name without the extension.
 *
 * Manifest: a text file of tab-separated lines `name file [N [options]]`;
 * blank lines and lines starting with '#' are skipped, as is a first line
 * whose first field is "name" (a header). N is an integer >= 4 or '-';
 * options are tighten's, separated by spaces (no quoting).
 *
 * A file field `knot NAME` or `link NAME` (or `knot:NAME`, `link:NAME`;
 * the words of `tightrope make`) names a knot of KnotInfo's table or a link
 * of LinkInfo's embedded in the program (topology/knot_table.h) instead of
 * a file: checked here (an unknown name is the line's error, with the
 * nearest names), made by the batch when the knot runs. A file whose path
 * begins with these words is given as ./knot... . A bare `knot` or `link`
 * is a missing name, not a file. */
int tr_batch_read(const char *src, tr_batch_list *out, tr_error *err);

/* Where the starts by name of l go: OUT/starts/NAME.vect (out: the batch's
 * output folder, or any stand-in where nothing is written, e.g. --list).
 * -1 out of memory. */
int tr_batch_place_named(tr_batch_list *l, const char *out);

/* The folder of OUT that the starts by name are made in. */
#define TR_BATCH_STARTS_DIR "starts"

/* The tighten options batch gives every run itself, which neither a
 * manifest nor the command line may set: NULL if `opt` is not one, else
 * why. */
const char *tr_batch_reserved_option(const char *opt);

/* Appends the words of field (tighten options separated by blanks, no
 * quoting; field is cut up) to *opts, each a copy; -1 out of memory. */
int tr_batch_split_options(char *field, char ***opts, int *nopts);

/* Whether name is a valid knot name (see tr_batch_knot). */
int tr_batch_name_ok(const char *name);

void tr_batch_list_free(tr_batch_list *l);

#endif
