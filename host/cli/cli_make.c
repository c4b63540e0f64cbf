/* tightrope make: writes a start curve (torus knot, circle, Hopf link,
 * simple clasp) in the format its file name asks for. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/cli_args.h"
#include "cli/cli_make_knot.h"
#include "curve/curve_io.h"
#include "curve/generate.h"
#include "engine/engine.h"

static void usage(FILE *out)
{
    fprintf(out,
            "usage: tightrope make torus P Q [--n N] -o OUT\n"
            "       tightrope make circle [--radius R] [--n N] -o OUT\n"
            "       tightrope make hopf [--n N] -o OUT\n"
            "       tightrope make clasp [--n N] [--height H] -o OUT\n"
            "       tightrope make knot NAME | --braid WORD | --pd CODE [--n N] [--as-drawn] -o OUT\n"
            "       tightrope make link NAME | --braid WORD [--n N] [--as-drawn] -o OUT\n"
            "\n"
            "Writes a start curve for a rope of radius 1, embedded with room to tighten.\n"
            "  torus P Q   torus knot T(P,Q) (P, Q coprime, |P|,|Q| >= 2), equilateral,\n"
            "              scaled so its radius of curvature is >= 2 and points more than\n"
            "              pi apart along it are >= 3 apart; default N 200\n"
            "  circle      round circle in the xy plane; default radius 3, N 64\n"
            "  hopf        two circles of radius 3 through each other's centre; N per circle, default 64\n"
            "  clasp       two open ropes hooked in perpendicular planes, the ends of one on\n"
            "              the plane z = +H, of the other on z = -H (plane constraints);\n"
            "              N per rope, default 100; default H 5 (at least 1.5)\n"
            "  knot NAME   a prime knot of KnotInfo's table: 0_1, 3_1 ... 10_165, 11a_1 ... 12n_888\n"
            "              (3.1, 11a1 read too): its minimal diagram (KnotInfo's PD code) or the\n"
            "              closure of its braid word, whichever is shorter relaxed (with --as-drawn\n"
            "              the closure as drawn); its type is checked\n"
            "              (Alexander polynomial, determinant, signature up to the mirror image, all\n"
            "              of the made curve) before it is written\n"
            "  link NAME   a prime link of LinkInfo's table to 9 crossings: L2a1{0} ... L9n27{1,1}\n"
            "              (L2a1 its first orientation, Rolfsen's 2^2_1 too); components and linking\n"
            "              numbers checked\n"
            "  --braid WORD  the closure of a braid word: \"1,1,-2,...\" (sigma_i as i, its inverse -i)\n"
            "  --pd CODE   a knot's PD code, \"[[1,5,2,4],[3,1,4,6],[5,3,6,2]]\" (KnotInfo's, KnotTheory's),\n"
            "              drawn in the plane and lifted at its crossings; checked against the\n"
            "              code's own invariants\n"
            "  Knots and links are relaxed as KnotPlot relaxes its knots (the strands push each\n"
            "  other apart, none passes another) from the closure or the drawing, then made\n"
            "  equilateral per component and scaled to thickness 1.25; default\n"
            "  N: edges of about 0.22 (tighten starts such a loose curve from N / 4). See\n"
            "  docs/knots.md.\n"
            "\n"
            "  -o, --output OUT  output file; its extension picks the format: .vect (VECT with\n"
            "                    plCurve constraints), .tsv (closed components), .txt (one closed\n"
            "                    component)\n"
            "  --n N             number of vertices\n"
            "  --as-drawn        knots and links: the braid closure (a name's too) or the PD\n"
            "                    code's drawing as it is, not relaxed (a looser start, 2 to 5\n"
            "                    times its tight length)\n"
            "Exit status: 0 written, 2 bad arguments or notation, an unknown name or the file could\n"
            "not be written, 1 a made curve not of the type asked for (nothing is left behind then).\n");
}

int tr_make_start_check(const tr_curve *c, tr_error *err)
{
    tr_engine_params prm;
    tr_engine_params_default(&prm);
    tr_engine *e = NULL;
    int rc = tr_engine_create(&e, c, "reference", &prm, err);
    tr_engine_destroy(e);
    return rc;
}

int tr_cmd_make(int argc, char **argv)
{
    const char *kind = NULL, *outpath = NULL, *braid = NULL, *pd = NULL;
    const char *pos[2] = {NULL, NULL};
    int npos = 0;
    size_t n = 0;
    int have_n = 0, have_radius = 0, have_height = 0, as_drawn = 0;
    double radius = 3.0, height = 5.0;

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        }
        int takes = !strcmp(a, "-o") || !strcmp(a, "--output") || !strcmp(a, "--n") || !strcmp(a, "-n") ||
                    !strcmp(a, "--radius") || !strcmp(a, "--height") || !strcmp(a, "--braid") ||
                    !strcmp(a, "--pd");
        if (takes) {
            if (i + 1 >= argc) {
                fprintf(stderr, "tightrope make: %s needs a value\n", a);
                return 2;
            }
            const char *v = argv[++i];
            if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
                outpath = v;
            } else if (!strcmp(a, "--braid")) {
                braid = v;
            } else if (!strcmp(a, "--pd")) {
                pd = v;
            } else if (!strcmp(a, "--n") || !strcmp(a, "-n")) {
                if (tr_arg_size(v, 3, (size_t)1 << 40, &n)) {
                    fprintf(stderr, "tightrope make: bad --n '%s' (a vertex count, an integer from 3 to 2^40)\n", v);
                    return 2;
                }
                have_n = 1;
            } else if (!strcmp(a, "--radius")) {
                if (tr_arg_double(v, -HUGE_VAL, HUGE_VAL, &radius)) {
                    fprintf(stderr, "tightrope make: bad --radius '%s'\n", v);
                    return 2;
                }
                have_radius = 1;
            } else {
                if (tr_arg_double(v, -HUGE_VAL, HUGE_VAL, &height)) {
                    fprintf(stderr, "tightrope make: bad --height '%s'\n", v);
                    return 2;
                }
                have_height = 1;
            }
            continue;
        }
        if (!strcmp(a, "--as-drawn")) {
            as_drawn = 1;
            continue;
        }
        if (a[0] == '-' && a[1] && !(a[1] >= '0' && a[1] <= '9')) {
            fprintf(stderr, "tightrope make: unknown option '%s' (see tightrope make --help)\n", a);
            return 2;
        }
        if (!kind) {
            kind = a;
        } else if (npos < 2) {
            pos[npos++] = a;
        } else {
            fprintf(stderr, "tightrope make: unexpected argument '%s'\n", a);
            return 2;
        }
    }
    if (!kind) {
        fprintf(stderr, "tightrope make: which curve? torus, circle, hopf, clasp, knot or link (see tightrope make "
                        "--help)\n");
        return 2;
    }
    if (!outpath) {
        fprintf(stderr, "tightrope make: no output file (-o OUT)\n");
        return 2;
    }
    if (tr_format_from_name(outpath) == TR_FORMAT_AUTO) {
        fprintf(stderr, "tightrope make: cannot tell the format of '%s' (use .vect, .tsv or .txt)\n", outpath);
        return 2;
    }
    if (!strcmp(kind, "knot") || !strcmp(kind, "link")) {
        int is_link = kind[0] == 'l';
        int given = (npos > 0) + (braid != NULL) + (pd != NULL);
        if (npos > 1) {
            fprintf(stderr, "tightrope make: %s takes one NAME, got '%s' and '%s'\n", kind, pos[0], pos[1]);
            return 2;
        }
        if (given != 1) {
            fprintf(stderr,
                    given == 0 ? "tightrope make: which %s? a NAME, --braid WORD%s (see tightrope make --help)\n"
                               : "tightrope make: %s takes one of NAME, --braid WORD%s\n",
                    kind, is_link ? "" : " or --pd CODE");
            return 2;
        }
        if (is_link && pd) {
            fprintf(stderr, "tightrope make: --pd makes knots only (a link: its NAME or --braid)\n");
            return 2;
        }
        if (have_radius || have_height) {
            fprintf(stderr, "tightrope make: %s is not an option of %s\n", have_radius ? "--radius" : "--height", kind);
            return 2;
        }
        return tr_make_knot_command(is_link, npos ? pos[0] : NULL, braid, pd, have_n ? n : 0, as_drawn, outpath,
                                    TIGHTROPE_VERSION);
    }
    if (braid || pd || as_drawn) {
        fprintf(stderr, "tightrope make: %s is an option of make knot and make link\n",
                braid ? "--braid" : pd ? "--pd" : "--as-drawn");
        return 2;
    }
    int is_torus = !strcmp(kind, "torus"), is_circle = !strcmp(kind, "circle"), is_hopf = !strcmp(kind, "hopf"),
        is_clasp = !strcmp(kind, "clasp");
    if (!is_torus && !is_circle && !is_hopf && !is_clasp) {
        fprintf(stderr, "tightrope make: unknown curve '%s' (torus, circle, hopf, clasp, knot or link)\n", kind);
        return 2;
    }
    if (npos != (is_torus ? 2 : 0)) {
        fprintf(stderr, is_torus ? "tightrope make: torus needs P and Q, e.g. 'torus 2 3'\n"
                                 : "tightrope make: %s takes no positional arguments\n",
                kind);
        return 2;
    }
    if ((have_radius && !is_circle) || (have_height && !is_clasp)) {
        fprintf(stderr, "tightrope make: %s is not an option of %s\n", have_radius && !is_circle ? "--radius" : "--height",
                kind);
        return 2;
    }

    tr_error err = {{0}};
    tr_curve c;
    int rc;
    char comment[512];
    if (is_torus) {
        int p, q;
        if (tr_arg_int(pos[0], INT_MIN, INT_MAX, &p) || tr_arg_int(pos[1], INT_MIN, INT_MAX, &q)) {
            fprintf(stderr, "tightrope make: bad torus knot '%s %s' (two integers)\n", pos[0], pos[1]);
            return 2;
        }
        if (!have_n)
            n = 200;
        rc = tr_make_torus(&c, p, q, n, &err);
        snprintf(comment, sizeof comment, "torus knot T(%d,%d), %zu vertices, equilateral", p, q, n);
    } else if (is_circle) {
        if (!have_n)
            n = 64;
        rc = tr_make_circle(&c, radius, n, &err);
        snprintf(comment, sizeof comment, "circle of radius %.17g, %zu vertices", radius, n);
    } else if (is_hopf) {
        if (!have_n)
            n = 64;
        rc = tr_make_hopf(&c, n, &err);
        snprintf(comment, sizeof comment, "hopf link: two circles of radius 3, %zu vertices each", n);
    } else {
        if (!have_n)
            n = 100;
        rc = tr_make_clasp(&c, n, height, &err);
        snprintf(comment, sizeof comment, "simple clasp: two open ropes of %zu vertices, ends on the planes z = +-%.17g",
                 n, height);
    }
    if (rc) {
        fprintf(stderr, "tightrope make: %s\n", err.msg);
        return 2;
    }
    if ((rc = tr_make_start_check(&c, &err))) {
        tr_curve_free(&c);
        fprintf(stderr, "tightrope make: %s: tighten would refuse it: %s\n", comment, err.msg);
        return rc == TR_ENOMEM ? 1 : 2;
    }
    char comments[1024];
    double length = tr_curve_length(&c);
    snprintf(comments, sizeof comments, "%s\nlength %.17g\nmade by tightrope %s", comment, length, TIGHTROPE_VERSION);
    rc = tr_curve_write(outpath, TR_FORMAT_AUTO, &c, comments, &err);
    size_t nv = c.nv;
    tr_curve_free(&c);
    if (rc) {
        fprintf(stderr, "tightrope make: %s\n", err.msg);
        return 2;
    }
    printf("%s: %s; %zu vertices in all, length %.10g\n", outpath, comment, nv, length);
    return 0;
}
