/* The knot and link tables the binary carries (issue 47): KnotInfo's prime
 * knots to 12 crossings and LinkInfo's prime links to 9, with their braid
 * words, PD codes and the invariants a made or tightened curve is checked
 * against. The data are data/knots/knotinfo_knots.tsv and linkinfo_links.tsv (scripts/knotinfo_extract.py,
 * GPL-3.0 KnotInfo through database_knotinfo), embedded at build time
 * (cmake/EmbedText.cmake), so the program finds them from any directory.
 *
 * Names: KnotInfo's (0_1, 3_1 ... 10_165, 11a_1 ... 12n_888) and LinkInfo's
 * (L2a1{0}, L9n27{1,1}; the unoriented L2a1 means its first orientation,
 * the Rolfsen name 2^2_1 too). Case does not matter, and 3.1, 3-1, 11a1 and
 * K3_1 are read as 3_1 and 11a_1. */
#ifndef TR_KNOT_TABLE_H
#define TR_KNOT_TABLE_H

#include "topology/alexander.h"
#include "topology/knot_notation.h"

/* Pairwise linking numbers kept for a link (the table's links have at most
 * 4 components: 6 pairs). */
#define TR_TABLE_MAX_PAIRS 10

typedef struct tr_table_entry {
    char name[24];       /* "3_1", "L2a1{0}" */
    char unoriented[16]; /* links: "L2a1"; knots: the name */
    char rolfsen[16];    /* links: "2^2_1"; knots: "" */
    int is_link;
    int components, crossings;
    tr_braid braid; /* the unknot: len 0 */
    tr_pd pd;       /* the unknot: n 0 */
    /* knots only: the Alexander polynomial (Conway-normalised), determinant */
    tr_alexander alexander;
    long long determinant;
    int has_signature, signature;
    double ropelength; /* KnotInfo's; NAN where it lists none */
    /* links: the linking matrix's upper triangle (pairs (0,1), (0,2) ...) */
    int npairs;
    int linking[TR_TABLE_MAX_PAIRS];
} tr_table_entry;

typedef struct tr_knot_table {
    int n;
    tr_table_entry *e;
} tr_knot_table;

/* The embedded knots and links, parsed; TR_EPARSE (naming the table's line)
 * if the embedded data are broken, which the build's tests rule out. */
int tr_knot_table_load(tr_knot_table *t, tr_error *err);
void tr_knot_table_free(tr_knot_table *t);

/* The entry called name, or NULL. want_link: 1 links only, 0 knots only,
 * -1 either. */
const tr_table_entry *tr_knot_table_find(const tr_knot_table *t, const char *name, int want_link);

/* The up to max names nearest name (edit distance of the normalised names,
 * the nearest first), of the kind want_link asks, joined by ", " into buf. */
void tr_knot_table_suggest(const tr_knot_table *t, const char *name, int want_link, char *buf, size_t bufsize);

/* The name as the table spells it (lower case, '_' between crossings and
 * index), for messages; into buf. */
void tr_knot_name_normalise(const char *name, char *buf, size_t bufsize);

#endif
