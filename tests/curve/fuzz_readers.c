/* libFuzzer target for the curve readers: any byte sequence must give either
 * a well-formed curve or one error line naming the input, never a crash, a
 * leak or undefined behaviour. A curve that parses must also survive
 * format -> parse unchanged (the writers' %.17g promise). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "curve/curve_io.h"

static void check_curve(const tr_curve *c)
{
    if (c->ncomp < 1 || c->nv < 2 || c->start[0] != 0 || c->start[c->ncomp] != c->nv)
        abort();
    for (int k = 0; k < c->ncomp; k++) {
        size_t n = tr_comp_nv(c, k);
        if (n < (c->closed[k] ? 3u : 2u))
            abort();
    }
    for (size_t i = 0; i < 3 * c->nv; i++)
        if (!isfinite(c->x[i]))
            abort();
    for (size_t i = 0; c->vcst && i < c->nv; i++)
        if (c->vcst[i] < -1 || c->vcst[i] >= c->ncst)
            abort();
}

static int same(const tr_curve *a, const tr_curve *b)
{
    return a->nv == b->nv && a->ncomp == b->ncomp && a->ncst == b->ncst &&
           !memcmp(a->x, b->x, 3 * a->nv * sizeof *a->x) &&
           !memcmp(a->start, b->start, (size_t)(a->ncomp + 1) * sizeof *a->start) &&
           !memcmp(a->closed, b->closed, (size_t)a->ncomp) &&
           (!a->ncst || !memcmp(a->vcst, b->vcst, a->nv * sizeof *a->vcst));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const tr_format fmts[] = {TR_FORMAT_VECT, TR_FORMAT_TSV, TR_FORMAT_KNOTPLOT, TR_FORMAT_AUTO};
    for (size_t f = 0; f < sizeof fmts / sizeof fmts[0]; f++) {
        tr_error err;
        tr_curve c;
        int rc = tr_curve_parse("fuzz", (const char *)data, size, fmts[f], &c, &err);
        if (rc != TR_OK) {
            if (rc == TR_EPARSE && (strncmp(err.msg, "fuzz:", 5) || strchr(err.msg, '\n')))
                abort();
            if (c.x || c.nv)
                abort();
            continue;
        }
        check_curve(&c);
        tr_format out = fmts[f] == TR_FORMAT_AUTO ? TR_FORMAT_VECT : fmts[f];
        char *text;
        size_t len;
        if (tr_curve_format(&c, out, "fuzz\nround trip", &text, &len, &err) == TR_OK) {
            tr_curve d;
            if (tr_curve_parse("again", text, len, out, &d, &err) != TR_OK || !same(&c, &d))
                abort();
            tr_curve_free(&d);
            free(text);
        }
        tr_curve_free(&c);
    }
    return 0;
}
