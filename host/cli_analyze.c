/* tightrope analyze: the paper's portrait of a tight knot (issue 5). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "analysis_plots.h"
#include "analysis_report.h"
#include "cli.h"
#include "contacts.h"
#include "curve_io.h"
#include "knot_analysis.h"
#include "thickness.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: tightrope analyze IN --out DIR [-m M] [--plots] [options]\n"
            "\n"
            "Curvature, torsion, symmetry and contact portrait of each closed component of IN\n"
            "(REFERENCE.md 3-5). The curve is first scaled to thickness 1 (rope radius 1).\n"
            "Writes into DIR (DIR/compK/ for a link): curvature.csv, torsion.csv, plateaus.csv,\n"
            "symmetry.csv, contacts.csv, sigma.csv, fixed_points.csv, summary.json, report.txt;\n"
            "with --plots also PNG plots drawn by gnuplot.\n"
            "\n"
            "options:\n"
            "  -m M               averaging block (default 10, the paper's; 1 = raw polygon)\n"
            "  --plots            draw PNGs with gnuplot (CSV files are written regardless)\n"
            "  --plateau-eps E    plateau = arcs with kappa >= 1 - E (default 1e-4)\n"
            "  --plateau-min K    plateaus need at least K arcs (default 2)\n"
            "  --jump-window w,W  one-sided fit windows [l-W, l-w], [l+w, l+W] (default 2.5me, w+max(0.03, 8me))\n"
            "  --jump-at l,...    also measure jumps at these positions (from the origin)\n"
            "  --sym-tol T        symmetry threshold, relative to the radius of gyration (default 1e-3)\n"
            "  --strut-tol T      contacts: struts up to (1 + T) x the shortest (default 1e-4; a converged\n"
            "                     knot needs less, a loose one more)\n"
            "  --contact-bin B    bin width for the contact functions (default max(4e, L/4000))\n"
            "  --power P          functional power for the cycles (default 9)\n"
            "  --paper / --no-paper  set the paper's trefoil values beside ours (default: when the\n"
            "                     knot is D3 with ropelength within 2%% of 32.743)\n"
            "  --no-scale         analyse the coordinates as given\n");
}

static int parse_list(const char *s, double *v, size_t max, size_t *n)
{
    *n = 0;
    while (*s && *n < max) {
        char *end;
        errno = 0;
        v[*n] = strtod(s, &end);
        if (end == s || errno)
            return -1;
        (*n)++;
        if (*end == ',')
            s = end + 1;
        else if (*end == '\0')
            return 0;
        else
            return -1;
    }
    return *s ? -1 : 0;
}

static int parse_double(const char *s, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    return (end == s || *end || errno || !isfinite(*v)) ? -1 : 0;
}

static int write_text(const char *dir, const char *name, char *text, tr_error *err)
{
    char path[4096];
    int len = snprintf(path, sizeof path, "%s/%s", dir, name);
    if (len < 0 || (size_t)len >= sizeof path) {
        free(text);
        return tr_fail(err, TR_EINVAL, "%s: output path too long", dir);
    }
    if (!text)
        return tr_fail(err, TR_ENOMEM, "out of memory writing %s", path);
    int rc = tr_write_file_atomic(path, text, strlen(text), err);
    free(text);
    return rc;
}

static int make_dir(const char *dir)
{
    if (mkdir(dir, 0777) == 0 || errno == EEXIST)
        return 0;
    return -1;
}

typedef struct cli_opts {
    tr_analysis_opts ao;
    double jump_at[64];
    double strut_tol;
    int plots, paper, scale;
} cli_opts;

/* One closed component: copy it into its own curve, scale to thickness 1,
 * measure it with its struts, analyse, write. Returns a process status. */
static int analyse_component(const tr_curve *c, int k, const char *in, const char *dir,
                             const cli_opts *o, int *plots_missing)
{
    tr_error err = {{0}};
    size_t nv = tr_comp_nv(c, k);
    unsigned char closed = 1;
    tr_curve one;
    if (tr_curve_alloc(&one, 1, &nv, &closed, &err) != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s\n", err.msg);
        return 1;
    }
    memcpy(one.x, c->x + 3 * c->start[k], 3 * nv * sizeof *one.x);
    int status = 1, rc;
    tr_thickness th;
    tr_strut_list sl = {0};
    tr_analysis an;
    memset(&an, 0, sizeof an);
    double scale = 1.0;
    if ((rc = tr_thickness_measure(&one, NULL, &th, NULL, &err)) != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s: thickness: %s\n", in, err.msg);
        goto out;
    }
    if (o->scale) {
        if (!(th.thickness > 0) || !isfinite(th.thickness)) {
            fprintf(stderr, "tightrope analyze: %s: component %d has no finite thickness\n", in, k);
            goto out;
        }
        scale = 1.0 / th.thickness;
        for (size_t i = 0; i < 3 * nv; i++)
            one.x[i] *= scale;
    }
    tr_thickness_opts to = {.strut_rel_tol = o->strut_tol};
    if ((rc = tr_thickness_measure(&one, &to, &th, &sl, &err)) != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s: thickness: %s\n", in, err.msg);
        goto out;
    }
    tr_contact_pair *pairs = NULL;
    size_t np = 0;
    double dmax = isfinite(th.dcsd) ? (1.0 + o->strut_tol) * th.dcsd : INFINITY;
    if ((rc = tr_contact_pairs_from_struts(one.x, nv, 0, sl.s, sl.n, dmax, &pairs, &np, &err)) !=
        TR_OK) {
        fprintf(stderr, "tightrope analyze: %s\n", err.msg);
        goto out;
    }
    rc = tr_analyze_component(one.x, nv, pairs, np, &o->ao, &an, &err);
    free(pairs);
    if (rc != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s: component %d: %s\n", in, k, err.msg);
        status = rc == TR_ENOMEM ? 1 : 2;
        goto out;
    }
    tr_report_ctx ctx = {in, k, scale, &th,
                         o->paper < 0 ? tr_report_is_trefoil_like(&an, &th) : o->paper};
    char *t;
    int bad = 0;
    bad |= tr_report_curvature_csv(&an, &t) || write_text(dir, "curvature.csv", t, &err);
    bad |= !bad && (tr_report_torsion_csv(&an, &t) || write_text(dir, "torsion.csv", t, &err));
    bad |= !bad && (tr_report_plateaus_csv(&an, &t) || write_text(dir, "plateaus.csv", t, &err));
    bad |= !bad && (tr_report_symmetry_csv(&an, &t) || write_text(dir, "symmetry.csv", t, &err));
    bad |= !bad && (tr_report_contacts_csv(&an, one.x, nv, &t) || write_text(dir, "contacts.csv", t, &err));
    if (an.have_sigma) {
        bad |= !bad && (tr_report_sigma_csv(&an, 4000, &t) || write_text(dir, "sigma.csv", t, &err));
        bad |= !bad && (tr_report_fixed_points_csv(&an, &t) || write_text(dir, "fixed_points.csv", t, &err));
    }
    bad |= !bad && (tr_report_summary_json(&an, &ctx, &t) || write_text(dir, "summary.json", t, &err));
    char *txt = NULL;
    bad |= !bad && tr_report_text(&an, &ctx, &txt);
    if (!bad) {
        fputs(txt, stdout);
        bad |= write_text(dir, "report.txt", txt, &err) != TR_OK;
    } else {
        free(txt);
    }
    if (bad) {
        fprintf(stderr, "tightrope analyze: writing %s: %s\n", dir, err.msg[0] ? err.msg : "out of memory");
        goto out;
    }
    if (o->plots) {
        rc = tr_analysis_plots(dir, &an, &err);
        if (rc == TR_EUNSUPPORTED) {
            fprintf(stderr, "tightrope analyze: no plots: %s; the CSV files are written\n", err.msg);
            *plots_missing = 1;
        } else if (rc != TR_OK) {
            fprintf(stderr, "tightrope analyze: plots: %s\n", err.msg);
            goto out;
        } else {
            printf("plots: %s/{curvature_torsion,plateau_zoom,accumulated_torsion%s}.png\n", dir,
                   an.have_sigma ? ",contact_map,sigma9" : "");
        }
    }
    status = 0;
out:
    tr_analysis_free(&an);
    tr_strut_list_free(&sl);
    tr_curve_free(&one);
    return status;
}

int tr_cmd_analyze(int argc, char **argv)
{
    cli_opts o;
    memset(&o, 0, sizeof o);
    o.strut_tol = 1e-4;
    o.paper = -1;
    o.scale = 1;
    const char *in = NULL, *out = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        double d;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "--plots")) {
            o.plots = 1;
        } else if (!strcmp(a, "--paper")) {
            o.paper = 1;
        } else if (!strcmp(a, "--no-paper")) {
            o.paper = 0;
        } else if (!strcmp(a, "--no-scale")) {
            o.scale = 0;
        } else if (a[0] == '-' && a[1] != '\0' && !v) {
            fprintf(stderr, "tightrope analyze: %s needs a value\n", a);
            return 2;
        } else if (!strcmp(a, "--out") || !strcmp(a, "-o")) {
            out = v, i++;
        } else if (!strcmp(a, "-m")) {
            if (parse_double(v, &d) || d < 1 || d != floor(d) || d > 1e6) {
                fprintf(stderr, "tightrope analyze: -m needs a positive integer, got '%s'\n", v);
                return 2;
            }
            o.ao.m = (size_t)d, i++;
        } else if (!strcmp(a, "--plateau-eps") || !strcmp(a, "--sym-tol") ||
                   !strcmp(a, "--strut-tol") || !strcmp(a, "--contact-bin") ||
                   !strcmp(a, "--plateau-min") || !strcmp(a, "--power")) {
            if (parse_double(v, &d) || !(d > 0)) {
                fprintf(stderr, "tightrope analyze: %s needs a positive number, got '%s'\n", a, v);
                return 2;
            }
            if (!strcmp(a, "--plateau-eps"))
                o.ao.plateau_eps = d;
            else if (!strcmp(a, "--sym-tol"))
                o.ao.sym_tol = d;
            else if (!strcmp(a, "--strut-tol"))
                o.strut_tol = d;
            else if (!strcmp(a, "--contact-bin"))
                o.ao.contact_bin = d;
            else if (!strcmp(a, "--plateau-min"))
                o.ao.plateau_min = (size_t)d;
            else
                o.ao.power = (int)d;
            i++;
        } else if (!strcmp(a, "--jump-window")) {
            double w[2];
            size_t n;
            if (parse_list(v, w, 2, &n) || n != 2 || !(w[0] >= 0) || !(w[1] > w[0])) {
                fprintf(stderr, "tightrope analyze: --jump-window needs w,W with 0 <= w < W, got '%s'\n", v);
                return 2;
            }
            o.ao.jump_w = w[0] > 0 ? w[0] : 1e-300;
            o.ao.jump_W = w[1], i++;
        } else if (!strcmp(a, "--jump-at")) {
            size_t n;
            if (parse_list(v, o.jump_at, 64, &n) || n == 0) {
                fprintf(stderr, "tightrope analyze: --jump-at needs a comma-separated list, got '%s'\n", v);
                return 2;
            }
            o.ao.jump_at = o.jump_at;
            o.ao.n_jump_at = n, i++;
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "tightrope analyze: unknown option '%s'\n", a);
            usage(stderr);
            return 2;
        } else if (!in) {
            in = a;
        } else {
            fprintf(stderr, "tightrope analyze: one input file only ('%s' and '%s')\n", in, a);
            return 2;
        }
    }
    if (!in || !out) {
        usage(stderr);
        return 2;
    }
    tr_error err = {{0}};
    tr_curve c;
    int rc = tr_curve_read(in, TR_FORMAT_AUTO, &c, &err);
    if (rc != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s\n", err.msg);
        return rc == TR_EIO || rc == TR_EPARSE ? 2 : 1;
    }
    if (make_dir(out)) {
        fprintf(stderr, "tightrope analyze: cannot create directory %s: %s\n", out, strerror(errno));
        tr_curve_free(&c);
        return 1;
    }
    int status = 0, nclosed = 0, plots_missing = 0;
    for (int k = 0; k < c.ncomp; k++) {
        if (!c.closed[k]) {
            fprintf(stderr, "tightrope analyze: %s: component %d is open; skipped (the portrait is for closed knots)\n", in, k);
            continue;
        }
        nclosed++;
        char dir[4096];
        if (c.ncomp > 1) {
            snprintf(dir, sizeof dir, "%s/comp%d", out, k);
            if (make_dir(dir)) {
                fprintf(stderr, "tightrope analyze: cannot create directory %s: %s\n", dir, strerror(errno));
                status = 1;
                break;
            }
        } else {
            snprintf(dir, sizeof dir, "%s", out);
        }
        int s = analyse_component(&c, k, in, dir, &o, &plots_missing);
        if (s > status)
            status = s;
    }
    tr_curve_free(&c);
    if (!nclosed) {
        fprintf(stderr, "tightrope analyze: %s has no closed component\n", in);
        return 2;
    }
    return status;
}
