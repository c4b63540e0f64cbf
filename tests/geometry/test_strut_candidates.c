/* This file contains the test of the strut candidate list
 * (tr_strut_candidates, geometry/struts.h) against a brute-force loop over
 * every pair of edges with the same two rules (the exclusion gap along the
 * curve, the segment distance below the cutoff), on a Hopf link (pairs
 * between components) and a wobbled circle (pairs within one component),
 * and that a pair listed before keeps its multiplier. */
#include <math.h>
#include <stdlib.h>

#include "curve/generate.h"
#include "geometry/neighbour_search.h"
#include "geometry/struts.h"
#include "segment_distance.h"
#include "testlib.h"

static void check_curve(tr_curve *c, double cutoff)
{
    tr_error err = {0};
    size_t nv = c->nv, *next = malloc(nv * sizeof *next);
    int *gap = malloc((size_t)c->ncomp * sizeof *gap);
    if (!next || !gap) {
        CHECK(next && gap);
        return;
    }
    for (int k = 0; k < c->ncomp; k++) {
        size_t st = c->start[k], n = tr_comp_nv(c, k);
        for (size_t j = 0; j < n; j++)
            next[st + j] = j + 1 < n ? st + j + 1 : st;
        gap[k] = tr_exclusion_gap(1.0, tr_comp_length(c, k) / (double)n);
    }
    tr_nsearch ns;
    REQUIRE_OK(tr_nsearch_build(&ns, c, &err));
    tr_strut_pair *list = NULL;
    size_t n = 0;
    REQUIRE_OK(tr_strut_candidates(&ns, c->x, next, gap, c->ncomp, cutoff, &list, &n, &err));
    /* brute force, in (a, b) order */
    size_t m = 0, bad = 0;
    for (size_t a = 0; a < nv; a++)
        for (size_t b = a + 1; b < nv; b++) {
            int ka = tr_curve_comp_of(c, a), kb = tr_curve_comp_of(c, b);
            if (ka == kb) {
                size_t g = b - a, ne = tr_comp_nv(c, ka);
                if (ne - g < g)
                    g = ne - g;
                if (g < (size_t)gap[ka])
                    continue;
            }
            double s, t, d = tr_segment_distance(c->x + 3 * a, c->x + 3 * next[a], c->x + 3 * b, c->x + 3 * next[b], &s, &t);
            if (!(d < cutoff))
                continue;
            if (m >= n || list[m].a != a || list[m].b != b)
                bad++;
            m++;
        }
    CHECK(m > 0);
    CHECK(m == n);
    CHECK(bad == 0);
    /* the multipliers carry over to a new list of the same pairs */
    for (size_t i = 0; i < n; i++)
        list[i].lam = (double)(i + 1);
    REQUIRE_OK(tr_strut_candidates(&ns, c->x, next, gap, c->ncomp, cutoff, &list, &n, &err));
    size_t kept = 0;
    for (size_t i = 0; i < n; i++)
        kept += list[i].lam == (double)(i + 1);
    CHECK(kept == n);
    free(list);
    tr_nsearch_free(&ns);
    free(next);
    free(gap);
}

static void run(void)
{
    tr_curve c = {0};
    tr_error err = {0};
    REQUIRE_OK(tr_make_hopf(&c, 60, &err));
    check_curve(&c, 3.5); /* the start is loose: its components are about 3 apart */
    tr_curve_free(&c);
    /* a circle of radius 1.05 with a wobble: opposite sides within 2.3 */
    REQUIRE_OK(tr_make_circle(&c, 1.05, 90, &err));
    for (size_t i = 0; i < c.nv; i++)
        c.x[3 * i + 2] += 0.1 * sin(4.0 * atan(1.0) * 6.0 * (double)i / (double)c.nv);
    check_curve(&c, 2.3);
    tr_curve_free(&c);
}

int main(void)
{
    run();
    return tr_test_finish("test_strut_candidates");
}
