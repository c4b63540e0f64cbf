/* The anatomy of one rope of a tight simple clasp (docs/physics.md 6.2), read
 * off the rope's raw inscribed-arc curvature: from each free end to the tip,
 * the straight end E (kappa 0, free of the other rope), the shoulder S
 * (kappa 1/2: the axis runs on a circle of radius 2 about the other rope's
 * tip), the first deep D1 (straight; 0.0078 wide in Starostin's solution),
 * the Gehring piece G (two lines of contact, kappa varying smoothly), the
 * second deep D2 (straight; 0.0004) and the kink K (kappa 1) at the tip.
 *
 * A boundary between two pieces is placed where a sharp step between their
 * levels would turn the rope as much as the vertices near it do (a vertex's
 * turning angle says how much of its cell is bent, not where), so it is known
 * to half an edge, plus the spread of the estimate over the windows and
 * levels it is taken with. A straight piece narrower than two edges shows as
 * a dip of one or two arcs: its width is then the turning the dip lacks over
 * the neighbours' curvature, reported as not resolved. */
#ifndef TR_CLASP_ANATOMY_H
#define TR_CLASP_ANATOMY_H

#include <stddef.h>

#include "analysis/arc_profile.h"
#include "util/error.h"

/* Published values (docs/physics.md 6.2; ../shared/REFERENCE.md 6.2). */
#define TR_CLASP_SHOULDER_KAPPA 0.5  /* 1/R_shoulder, R = 2: the other rope's radius doubled */
#define TR_CLASP_KINK_KAPPA 1.0      /* the curvature limit 1/R, R = 1 */
#define TR_CLASP_D1_STAROSTIN 0.0078 /* Starostin 2003 */
#define TR_CLASP_D1_SPFEM 0.008      /* Przybyl & Pieranski, SP-FEM at N = 31992, edge 0.00026 */
#define TR_CLASP_D2_STAROSTIN 0.0004 /* Starostin 2003 */

/* The pieces in order from a free end to the tip. */
enum { TR_CLASP_E, TR_CLASP_S, TR_CLASP_D1, TR_CLASP_G, TR_CLASP_D2, TR_CLASP_K, TR_CLASP_NPIECES };
extern const char *const tr_clasp_piece_names[TR_CLASP_NPIECES];

typedef enum tr_piece_status {
    TR_PIECE_RESOLVED = 0, /* found; a straight piece at least two edges wide with a straight arc on it */
    TR_PIECE_DIP,          /* a straight piece seen only as a dip narrower than that: width from the
                              turning the dip lacks; not resolved */
    TR_PIECE_UNSEEN        /* not resolved: no trace of it at this edge length (why says) */
} tr_piece_status;

typedef struct tr_clasp_piece {
    tr_piece_status status;
    double from, to;          /* extent, arclength from this half's free end (NAN where unseen) */
    double from_err, to_err;  /* each boundary's uncertainty */
    double width, err;        /* its length and uncertainty (NAN where unseen) */
    size_t arcs;              /* arcs whose cells lie wholly on it (centred on it, when none does;
                                 a dip: the arcs that dip) */
    double kappa_min, kappa_mean, kappa_max; /* over those arcs (NAN if none) */
    char why[240];            /* why it is not resolved (empty when it is) */
} tr_clasp_piece;

typedef struct tr_clasp_half {
    size_t end_vertex;        /* the free end this half starts from: 0 or n - 1 */
    double length;            /* from that end to the tip */
    tr_clasp_piece piece[TR_CLASP_NPIECES];
} tr_clasp_half;

typedef struct tr_clasp_rope {
    int found;                /* 0: not read as a tight clasp rope; why says what is missing */
    char why[256];
    size_t n;                 /* vertices */
    double L, e;              /* length, mean edge */
    double tip, tip_err;      /* the middle of K, arclength from vertex 0 */
    tr_clasp_half half[2];    /* from vertex 0, from vertex n - 1 */
    double kink_width, kink_width_err;     /* K across the tip */
    double kink_kappa, kink_min, kink_max; /* over K's arcs */
    double shoulder_kappa;    /* mean of the pair averages over both shoulders */
    double shoulder_pair_dev; /* max |pair average - 1/2| there */
    double shoulder_alt;      /* max |kappa - 1/2| there: the period-2 alternation */
} tr_clasp_rope;

/* p: the open profile of one rope (tr_arc_profile_compute_open, raw, not
 * averaged). A rope that is not a tight clasp's (no kink at curvature 1, no
 * shoulder at 1/2, pieces out of order) gives TR_OK with found = 0 and the
 * reason in why; errors are for a closed profile or memory. */
int tr_clasp_rope_anatomy(const tr_arc_profile *p, tr_clasp_rope *out, tr_error *err);

#endif
