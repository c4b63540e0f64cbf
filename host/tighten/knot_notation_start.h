/* The one way from notation to a start curve (issue 47): a name of
 * KnotInfo's or LinkInfo's table, a braid word or a knot's PD code, made
 * into a curve (knot_start.h) and its type checked against the notation's,
 * with the words that say what was made and what was checked. `make knot`,
 * `batch`'s starts by name and the library's tightrope_make all come here,
 * so they make, check and refuse alike. */
#ifndef TR_KNOT_NOTATION_START_H
#define TR_KNOT_NOTATION_START_H

#include <stddef.h>

#include "curve/curve.h"
#include "util/error.h"

/* What to make: exactly one of name, braid and pd. */
typedef struct tr_knot_notation {
    const char *name;  /* a table name: 7_4, 7.4, 11a_1, L6a4{0,0} ... */
    const char *braid; /* a braid word's text, "1,1,-2" (tr_braid_parse) */
    const char *pd;    /* a knot's PD code's text (tr_pd_parse) */
    int want_link;     /* 0 a knot, 1 a link, -1 either */
    size_t n;          /* vertices in all; 0: edges of about TR_KNOT_START_EDGE */
    int as_drawn;      /* 1: the braid closure or PD layout as drawn, not relaxed (knot_start.h) */
} tr_knot_notation;

/* What was made, in words for a file's comments and a command's output. */
typedef struct tr_knot_made {
    /* "knot 7_4 (KnotInfo), closure of its 4-strand braid"; empty until
     * the notation was read */
    char what[512];
    /* "type checked: Alexander polynomial 4 -7 4, ..., as 7_4's", or for
     * a braid word (which names no type) "invariants: ..." */
    char check[1024];
    double thickness;  /* the start's as made (NAN for the unknot's circle) */
    int from_table;    /* the notation is the table's (its source and licence go in the file) */
    int other_kind;    /* on TR_EINVAL: the name is in the table, as the other kind */
    char other_name[64]; /* that entry's name */
    int braid_components; /* on TR_EINVAL: a braid refused for its closure's components, their count */
} tr_knot_made;

/* Makes the start *nt describes into out (freed on failure), filling
 * *made. TR_EINVAL: bad notation (the parser's message), a name not in the
 * table (the nearest ones named; made->other_kind when it is the other
 * kind's), a braid whose closure is not the kind asked for
 * (made->braid_components), a PD code asked for a link, too few vertices;
 * TR_EGEOMETRY: the curve made is not of the notation's type, its type
 * could not be checked, or the layout cannot be made thick; TR_EPARSE or
 * TR_EIO: the embedded table; TR_ENOMEM. A bare braid word names no type:
 * its invariants go into made->check where they can be computed, and
 * nothing is refused where they cannot. The messages are one line each
 * and name what was being made. */
int tr_knot_start_make(const tr_knot_notation *nt, tr_curve *out, tr_knot_made *made, tr_error *err);

#endif
