/* What `tightrope batch` tightens: the knots of a manifest or of a folder of
 * curve files, in their order, each with its start file, its N and the
 * tighten options of its own. Reading checks everything a run of hours
 * would otherwise fail on late (a missing start, a bad N, a duplicate name,
 * an option batch sets itself) and names the manifest's FILE:LINE. */
#ifndef TR_BATCH_MANIFEST_H
#define TR_BATCH_MANIFEST_H

#include <stddef.h>

#include "util/error.h"

/* Longest knot name: it names the knot's files in the output folder. */
#define TR_BATCH_NAME_MAX 200

typedef struct tr_batch_knot {
    char *name;  /* [A-Za-z0-9._+-], not starting with '.' or '-'; unique */
    char *file;  /* the start curve; a manifest's relative paths are taken from its folder */
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
 * options are tighten's, separated by spaces (no quoting). */
int tr_batch_read(const char *src, tr_batch_list *out, tr_error *err);

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
