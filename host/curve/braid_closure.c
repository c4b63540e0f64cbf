/* The closed braid as a space curve (braid_closure.h). */
#include "curve/braid_closure.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TR_PI 3.14159265358979323846
#define BRAID_HEIGHT 0.5

/* Point of the strand that is at position p at the start of slot k, at
 * fraction u of the slot; *p_next gets its position at the slot's end. */
static void strand_point(const int *word, int len, double r0, int k, int p, double u, double *x, int *p_next)
{
    int g = word[k], i = abs(g) - 1; /* exchanges positions i and i+1 */
    double s = 0.5 * (1 - cos(TR_PI * u)), sn = sin(TR_PI * u), bump = BRAID_HEIGHT * sn * sn;
    double r = r0 + p, z = 0;
    *p_next = p;
    if (p == i) { /* moves outwards */
        r = r0 + i + s;
        z = g > 0 ? bump : -bump;
        *p_next = i + 1;
    } else if (p == i + 1) { /* moves inwards */
        r = r0 + i + 1 - s;
        z = g > 0 ? -bump : bump;
        *p_next = i;
    }
    double theta = 2 * TR_PI * (k + u) / len;
    x[0] = r * cos(theta);
    x[1] = r * sin(theta);
    x[2] = z;
}

int tr_make_braid_closure(tr_curve *out, int strands, const int *word, int len, int samples, tr_error *err)
{
    memset(out, 0, sizeof *out);
    if (strands < 2 || strands > 64)
        return tr_fail(err, TR_EINVAL, "a braid on %d strands (2 to 64)", strands);
    if (len < 1)
        return tr_fail(err, TR_EINVAL, "an empty braid word");
    if (samples < 4)
        return tr_fail(err, TR_EINVAL, "%d samples per slot (at least 4)", samples);
    for (int k = 0; k < len; k++)
        if (word[k] == 0 || abs(word[k]) > strands - 1)
            return tr_fail(err, TR_EINVAL, "braid generator %d at letter %d: not in 1..%d or its inverse", word[k],
                           k + 1, strands - 1);
    /* the permutation's cycles */
    int perm[64], comp_of[64], turns[64], first[64];
    for (int p = 0; p < strands; p++) {
        int q = p, nx;
        for (int k = 0; k < len; k++) {
            double dummy[3];
            strand_point(word, len, 0, k, q, 0, dummy, &nx);
            q = nx;
        }
        perm[p] = q;
        comp_of[p] = -1;
    }
    int nc = 0;
    for (int p = 0; p < strands; p++) {
        if (comp_of[p] >= 0)
            continue;
        first[nc] = p;
        turns[nc] = 0;
        for (int q = p; comp_of[q] < 0; q = perm[q]) {
            comp_of[q] = nc;
            turns[nc]++;
        }
        nc++;
    }
    size_t nv[64] = {0};
    unsigned char closed[64] = {0};
    for (int c = 0; c < nc; c++) {
        nv[c] = (size_t)turns[c] * (size_t)len * (size_t)samples;
        closed[c] = 1;
    }
    int rc = tr_curve_alloc(out, nc, nv, closed, err);
    if (rc)
        return rc;
    double r0 = fmax(1.2, 2.0 * len / (2 * TR_PI));
    for (int c = 0; c < nc; c++) {
        double *x = out->x + 3 * out->start[c];
        int p = first[c];
        size_t v = 0;
        for (int t = 0; t < turns[c]; t++)
            for (int k = 0; k < len; k++) {
                int nx = p;
                for (int m = 0; m < samples; m++)
                    strand_point(word, len, r0, k, p, (double)m / samples, x + 3 * v++, &nx);
                p = nx;
            }
    }
    return 0;
}
