/* The whole portrait of one closed component (docs/physics.md 3-5): symmetry and origin,
 * m-averaged inscribed-arc curvature and torsion, kappa = 1 plateaus and the
 * jumps at their ends, contact functions and the cycles of sigma-^9. All
 * positions in the result are arclengths measured from the chosen origin
 * along the input direction, in [0, L). */
#ifndef TR_PORTRAIT_H
#define TR_PORTRAIT_H

#include <stddef.h>

#include "analysis/contact_functions.h"
#include "analysis/arc_profile.h"
#include "util/error.h"
#include "analysis/profile_features.h"
#include "analysis/shape_average.h"
#include "analysis/symmetry.h"

typedef struct tr_analysis_opts {
    size_t m;             /* averaging block; 0: tr_analysis_default_m (the paper's window) */
    double plateau_eps;   /* plateau level 1 - eps; <= 0: 1e-4 */
    size_t plateau_min;   /* minimum arcs at 1 - eps in a plateau; 0: 2 */
    double plateau_edge;  /* a plateau extends over arcs with kappa >= 1 - edge on either side
                             and across dips to that level; <= 0: 0.02 (at least eps) */
    double jump_w, jump_W;/* one-sided fit windows; <= 0: w = 2 m e, W = w + max(0.03, 4 m e) */
    double sym_tol;       /* relative symmetry threshold; <= 0: 1e-3 */
    double contact_bin;   /* bin width for the contact functions; <= 0: max(4 e, L/4000) */
    int power;            /* functional power for the cycles; 0: 9 */
    const double *jump_at;/* extra points (from the origin) where jumps are measured */
    size_t n_jump_at;
} tr_analysis_opts;

/* A jump measured at every symmetry image of a representative point and
 * combined: mean and an error that adds the fits' errors to the scatter
 * among the images. Sign convention: kappa jumps as (plateau side - outside)
 * at plateau ends, (right - left) elsewhere; alpha jumps always right - left. */
typedef struct tr_jump_summary {
    double at;       /* representative position (from the origin) */
    double jump, err;
    int images;      /* how many images were measured */
} tr_jump_summary;

typedef struct tr_analysis {
    size_t n;        /* input vertices */
    double L;        /* input polygon length */
    size_t m;
    int m_default;   /* m was chosen by tr_analysis_default_m (opts.m was 0), not given */
    tr_symmetry sym;
    tr_averaged_knot avg;  /* positions from the origin */
    tr_arc_profile prof;   /* on avg, positions from the origin */
    tr_plateau *plateaus;
    size_t nplateaus;
    int have_l12;          /* a plateau was found inside a sector (D3) or at all */
    double l1, l2, l1_err, l2_err;  /* representative plateau ends (D3: reduced to [0, L/6)) */
    tr_jump_summary dkappa1, dkappa2, dalpha1, dalpha2;
    tr_jump_summary *extra_kappa, *extra_alpha; /* at opts.jump_at */
    size_t n_extra;
    double jump_w, jump_W;
    /* contacts */
    tr_contact_pair *pairs;  /* positions from the origin */
    size_t npairs;
    int have_sigma;
    char sigma_msg[1024];     /* why not, when !have_sigma */
    tr_contact_fn sigma_minus, sigma_plus;
    double sigma_inverse_err; /* max |sigma+(sigma-(l)) - l| over a grid */
    int power;
    double rotation_number;  /* of sigma- (lift advance per turn / L); 4/9 for the 9-cycles */
    double gap_min, gap_max; /* range of ((sigma-^power(l) - l + L/2) mod L) - L/2 */
    tr_fixed_point *fixed;
    size_t nfixed;
    tr_cycle *cycles;
    size_t ncycles;
} tr_analysis;

/* The arclength over which Przybyl & Pieranski averaged (REFERENCE.md 3.1,
 * the paper's section 3): their K_p^(10), m = 10 blocks of the N = 200640
 * trefoil's edges e_av = 1.63192456437e-4 (rope radius 1), so the window is
 * 10 x 1.63192456437e-4 = 1.632e-3. The window, not m, is what suppresses
 * the discretisation artefacts without smearing the plateau ends: a fixed m
 * averages over m L/N, which at N = 2400 (m = 10: 0.136, near the plateau
 * width 0.161) drew the trefoil's kappa = 1 plateaus down to a peak of 0.89. */
#define TR_PAPER_WINDOW_ARCLENGTH (10.0 * 1.63192456437e-4)

/* The default block: m = max(1, round(s / e)), s the paper's window, e = L/n
 * the mean edge of a closed polygon of length L (in rope radii: the curve at
 * thickness 1), and at most n/4 so that 4 averaged vertices remain. The
 * paper's own N = 200640, L_p = 32.742934460 gives its m = 10; any N below
 * about 30 000 for the trefoil gives m = 1. 1 when L or n is unusable. */
size_t tr_analysis_default_m(double L, size_t n);

/* x: closed component of n vertices; pairs: contacts (arclengths on x, any
 * origin), may be empty. */
int tr_analyze_component(const double *x, size_t n, const tr_contact_pair *pairs, size_t npairs,
                         const tr_analysis_opts *opts, tr_analysis *out, tr_error *err);
void tr_analysis_free(tr_analysis *a);

#endif
