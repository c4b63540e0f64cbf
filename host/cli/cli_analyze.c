/* This file contains `tightrope analyze`: the paper's portrait of a tight knot
 * (docs/physics.md 3-5). */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "analysis/analysis_plots.h"
#include "analysis/analysis_report.h"
#include "analysis/clasp_plots.h"
#include "cli/cli.h"
#include "cli/cli_args.h"
#include "cli/cli_clasp.h"
#include "cli/cli_gnuplot.h"
#include "cli/cli_interrupt.h"
#include "analysis/contact_functions.h"
#include "curve/curve_io.h"
#include "analysis/open_rope.h"
#include "analysis/portrait.h"
#include "analysis/tube_mesh.h"
#include "analysis/tube_picture.h"
#include "analysis/tube_script.h"
#include "analysis/tube_views.h"
#include "oracle/thickness.h"
#include "util/out_folder.h"

/* The record analyze keeps in its folder of the files it wrote there (out_folder.h). */
#define ANALYZE_RECORD ".tightrope-analyze"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: tightrope analyze IN --out DIR [-m M] [--plots] [options]\n"
            "\n"
            "Curvature, torsion, symmetry and contact portrait of each closed component of IN\n"
            "(docs/physics.md 3-5); curvature and torsion profiles of each open one (a rope: curvature.csv,\n"
            "torsion.csv, summary.json, report.txt). Two open ropes are read as a simple clasp: each rope's\n"
            "pieces E, S, D1, G, D2, K from its free ends to its tip, its symmetry and the ropes' congruence\n"
            "in summary.json, report.txt and pieces.csv; with --plots clasp_curvature.png, clasp_d1.png and clasp_d2.png\n"
            "(docs/physics.md 6.3). The curve is first scaled to thickness 1 (rope radius 1).\n"
            "Writes into DIR (DIR/compK/ for a link): curvature.csv, torsion.csv, plateaus.csv,\n"
            "symmetry.csv, contacts.csv, sigma.csv, fixed_points.csv, summary.json, report.txt;\n"
            "with --plots also PNG plots drawn by gnuplot, and pictures of the tube (radius 1) shaded:\n"
            "tube_front.png (along the symmetry axis), tube_top.png, tube_side.png and tube_struts.png\n"
            "(the struts inside the translucent tube), kappa = 1 stretches (the plateaus) and contacts marked.\n"
            "All of a run's files or none: they are written aside and moved into DIR when every one is\n"
            "(an interrupt, SIGINT/SIGTERM/SIGHUP, or a failure leaves DIR as it was). DIR/" ANALYZE_RECORD "\n"
            "lists what analyze wrote there; a later run replaces or removes only those files, while\n"
            "unchanged, and refuses to write over anything else (a file of yours, the input).\n"
            "\n"
            "options:\n"
            "  -m M               averaging block, 1 = raw polygon, at most N/4 (default: the paper's\n"
            "                     window of arclength 0.00163 = 10 of its N = 200640 edges, in edges:\n"
            "                     max(1, round(0.00163 N / L)), so m = 1 below N ~ 30000 for a trefoil)\n"
            "  --plots            also draw PNGs with gnuplot (needed on PATH)\n"
            "  --tube-size PX     the tube pictures' width and height, 200 to 4000 pixels (default 720)\n"
            "  --plateau-eps E    plateau = arcs with kappa >= 1 - E, 0 < E < 1 (default 1e-4)\n"
            "  --plateau-min K    plateaus need at least K arcs at 1 - E, an integer >= 1 (default 2)\n"
            "  --plateau-edge G   a plateau extends over neighbouring arcs with kappa >= 1 - G and\n"
            "                     across dips to that level, E <= G < 1 (default 0.02)\n"
            "  --jump-window w,W  one-sided fits: lines on [l-W, l-w], [l+w, l+W], quadratics out to\n"
            "                     2W-w (the estimate) (default 2me, w+max(0.03, 4me))\n"
            "  --jump-at l,...    also measure jumps at these positions (from the origin)\n"
            "  --sym-tol T        symmetry threshold, relative to the radius of gyration, 0 < T <= 1\n"
            "                     (default 1e-3)\n"
            "  --strut-tol T      contacts: struts up to (1 + T) x the shortest, 0 < T <= 1\n"
            "                     (default 1e-4; a converged knot needs less, a loose one more)\n"
            "  --contact-bin B    bin width for the contact functions, L x 1e-7 to L/8 of the scaled knot\n"
            "                     (default max(4e, L/4000))\n"
            "  --power P          functional power for the cycles, an integer 1 to 100 (default 9)\n"
            "  --paper / --no-paper  set the paper's trefoil values beside ours (default: when the\n"
            "                     knot is D3 with ropelength within 2%% of 32.743)\n"
            "  --no-scale         analyse the coordinates as given\n"
            "  --mesh FILE.ply    also write the rope as a closed triangulated tube of radius 1 around\n"
            "                     every component (open ropes capped), ASCII PLY for ParaView or Blender\n"
            "  --mesh-sides K     vertices per ring of the tube, 3 to 1024 (default 16)\n"
            "\n"
            "Exit status: 0 written; 2 bad input, option or unwritable output, or --plots without\n"
            "gnuplot; 1 out of memory or gnuplot failed. Nothing is written unless it is 0.\n");
}

/* Comma-separated finite numbers. */
static int parse_list(const char *s, double *v, size_t max, size_t *n)
{
    *n = 0;
    while (*s && *n < max) {
        char *end;
        errno = 0;
        v[*n] = strtod(s, &end);
        if (end == s || errno || !isfinite(v[*n]))
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

typedef struct cli_opts {
    tr_analysis_opts ao;
    double jump_at[64];
    double strut_tol;
    int plots, paper, scale;
    const char *mesh;  /* --mesh FILE or NULL */
    size_t mesh_sides;
    int tube_px;       /* --tube-size, 0: the default */
} cli_opts;

/* One component, analysed and not yet written. */
typedef struct comp_result {
    int k;
    int open;         /* an open rope: rope holds its profiles, an is empty */
    tr_open_rope rope;
    tr_curve one;     /* the component alone, scaled */
    double scale;
    tr_thickness th;
    tr_analysis an;
} comp_result;

static void comp_result_free(comp_result *r)
{
    tr_analysis_free(&r->an);
    tr_open_rope_free(&r->rope);
    tr_curve_free(&r->one);
}

/* Copies component k into its own curve, scales it to thickness 1, measures
 * it with its struts and analyses it. Returns a process status: 0, 1 (could
 * not be done), 2 (the input or an option is wrong for it; *optbad when an
 * option is). Prints its own one-line message. */
static int analyse_component(const tr_curve *c, int k, const char *in, const cli_opts *o,
                             comp_result *r, int *optbad)
{
    tr_error err = {{0}};
    memset(r, 0, sizeof *r);
    r->k = k;
    r->scale = 1.0;
    size_t nv = tr_comp_nv(c, k);
    r->open = !c->closed[k];
    if (tr_curve_component(&r->one, c, k, &err) != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s\n", err.msg);
        return 1;
    }
    int status = 1, rc;
    tr_strut_list sl = {0};
    if ((rc = tr_thickness_measure(&r->one, NULL, &r->th, NULL, &err)) != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s: component %d: thickness: %s\n", in, k, err.msg);
        status = rc == TR_ENOMEM ? 1 : 2;
        goto fail;
    }
    if (!o->scale && tr_curve_scale_exponent(&r->one)) {
        /* the oracle measures such a curve in a rescaled frame (curve.h),
         * the analysis would lose its squared distances */
        fprintf(stderr, "tightrope analyze: %s: component %d has thickness %.3g, too far from 1 to analyse "
                        "in its own units; drop --no-scale\n", in, k, r->th.thickness);
        status = 2;
        goto fail;
    }
    if (o->scale) {
        if (!(r->th.thickness > 0) || !isfinite(r->th.thickness)) {
            fprintf(stderr, "tightrope analyze: %s: component %d has no finite thickness\n", in, k);
            status = 2;
            goto fail;
        }
        r->scale = 1.0 / r->th.thickness;
        tr_curve_scale_by(&r->one, r->scale);
    }
    tr_thickness_opts to = {.strut_rel_tol = o->strut_tol};
    if ((rc = tr_thickness_measure(&r->one, &to, &r->th, &sl, &err)) != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s: component %d: thickness: %s\n", in, k, err.msg);
        status = rc == TR_ENOMEM ? 1 : 2;
        goto fail;
    }
    if (r->open) { /* profiles only: no contacts or symmetry on an open rope */
        tr_strut_list_free(&sl);
        if ((rc = tr_open_rope_analyze(r->one.x, nv, &r->rope, &err)) == TR_OK)
            return 0;
        fprintf(stderr, "tightrope analyze: %s: component %d: %s\n", in, k, err.msg);
        status = rc == TR_ENOMEM ? 1 : 2;
        goto fail;
    }
    /* The bin must be read against this component's length after scaling. */
    double L = r->th.length;
    if (o->ao.contact_bin > 0 && !(o->ao.contact_bin >= TR_CONTACT_BIN_MIN_REL * L &&
                                   o->ao.contact_bin <= TR_CONTACT_BIN_MAX_REL * L)) {
        fprintf(stderr,
                "tightrope analyze: --contact-bin %g outside [%.6g, %.6g] (L x %g to L / 8) for "
                "component %d of %s, L = %.6g\n",
                o->ao.contact_bin, TR_CONTACT_BIN_MIN_REL * L, TR_CONTACT_BIN_MAX_REL * L,
                TR_CONTACT_BIN_MIN_REL, k, in, L);
        *optbad = 1;
        status = 2;
        goto fail;
    }
    tr_contact_pair *pairs = NULL;
    size_t np = 0;
    double dmax = isfinite(r->th.dcsd) ? (1.0 + o->strut_tol) * r->th.dcsd : INFINITY;
    if ((rc = tr_contact_pairs_from_struts(r->one.x, nv, 0, sl.s, sl.n, dmax, &pairs, &np, &err)) !=
        TR_OK) {
        fprintf(stderr, "tightrope analyze: %s: component %d: %s\n", in, k, err.msg);
        goto fail;
    }
    rc = tr_analyze_component(r->one.x, nv, pairs, np, &o->ao, &r->an, &err);
    free(pairs);
    if (rc != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s: component %d: %s\n", in, k, err.msg);
        if (rc == TR_EINVAL)
            *optbad = 1;
        status = rc == TR_ENOMEM ? 1 : 2;
        goto fail;
    }
    tr_strut_list_free(&sl);
    return 0;
fail:
    tr_strut_list_free(&sl);
    comp_result_free(r);
    return status;
}

/* A message with the staging folder's paths shown as the folder's, where
 * the user will look (out_folder.h). */
static void say(const tr_out_folder *of, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void say(const tr_out_folder *of, const char *fmt, ...)
{
    char line[2400], shown[2400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    fputs(tr_out_folder_shown(of, line, shown, sizeof shown), stderr);
}

/* An open rope's tables, summary and report into dir, which exists (in
 * the stage of of); with clasp (one of a clasp's two ropes) its anatomy in
 * them, pieces.csv, and with --plots the paper's Fig. 3 and 4. Returns a
 * process status; an interrupt is 1, unreported. */
static int write_open_rope(comp_result *r, const char *in, const char *dir, const tr_out_folder *of,
                           const cli_opts *o, const tr_clasp_report *clasp)
{
    tr_error err = {{0}};
    tr_report_ctx ctx = {in, r->k, r->scale, &r->th, 0};
    const char *names[] = {"curvature.csv", "torsion.csv", "summary.json", "report.txt", "pieces.csv"};
    int found = clasp && clasp->rope->found;
    size_t nw = found ? 5 : 4;
    for (size_t i = 0; i < nw; i++) {
        char *t = NULL;
        int fmt = i == 0   ? tr_open_rope_curvature_csv(&r->rope, &t)
                  : i == 1 ? tr_open_rope_torsion_csv(&r->rope, &t)
                  : i == 2 ? tr_open_rope_summary_json(&r->rope, &ctx, clasp, &t)
                  : i == 3 ? tr_open_rope_report_text(&r->rope, &ctx, clasp, &t)
                           : tr_clasp_pieces_csv(clasp->rope, &t);
        if (fmt == TR_OK && i == 3)
            fputs(t, stdout);
        int rc = fmt == TR_OK ? write_text(dir, names[i], t, &err) : TR_ENOMEM;
        if (rc == TR_ENOMEM) {
            say(of, "tightrope analyze: writing %s: out of memory\n", dir);
            return 1;
        }
        if (rc != TR_OK) {
            say(of, "tightrope analyze: writing %s: %s\n", dir, err.msg);
            return 2;
        }
    }
    if (o->plots && found) {
        char title[256];
        const char *base = strrchr(in, '/');
        snprintf(title, sizeof title, "%.200s, rope %d", base ? base + 1 : in, r->k);
        int rc = tr_cli_clasp_draw(dir, clasp->rope, title, &err);
        if (rc == TR_OK) {
            char x[1100];
            printf("plots: %s/{clasp_curvature,clasp_d1,clasp_d2}.png\n", tr_out_folder_shown(of, dir, x, sizeof x));
        } else {
            if (rc != TR_EINTERRUPTED)
                say(of, "tightrope analyze: plots: %s\n", err.msg);
            return 1;
        }
    } else if (o->plots) {
        fprintf(stderr, "tightrope analyze: %s: component %d is open: plots are drawn for a clasp's ropes only "
                        "(%s); the CSV files are written\n", in, r->k,
                clasp ? clasp->rope->why : "not one of two open ropes");
    }
    return 0;
}

/* Writes DIR/plots.gp and has gnuplot draw it there (its output in
 * DIR/gnuplot.log). TR_EUNSUPPORTED if gnuplot is missing, TR_EIO if it
 * fails. */
static int draw_plots(const char *dir, const tr_analysis *an, tr_error *err)
{
    if (!tr_gnuplot_available())
        return tr_fail(err, TR_EUNSUPPORTED, "gnuplot not found on PATH (Debian package gnuplot-nox)");
    tr_plot_script ps;
    int rc = tr_analysis_plots_script(dir, an, &ps, err);
    if (rc != TR_OK)
        return rc;
    return tr_gnuplot_draw(dir, "plots.gp", "gnuplot.log", &ps, err);
}

/* The tube pictures of one analysed component: DIR/tube.dat,
 * DIR/struts.dat and DIR/tube.gp, drawn by gnuplot (its output in
 * DIR/tube_gnuplot.log) into DIR/tube_{front,top,side,struts}.png, px
 * pixels square. gnuplot is known to be there. */
static int draw_tube(const char *dir, const comp_result *r, const char *in, int px, tr_error *err)
{
    tr_tube_picture tp;
    int rc = tr_tube_picture_build(r->one.x, r->one.nv, &r->an, 0, 40, &tp, err);
    if (rc != TR_OK)
        return rc;
    tr_tube_views views;
    tr_tube_views_choose(r->one.x, r->one.nv, &r->an.sym, &views);
    char title[512];
    const char *base = strrchr(in, '/');
    snprintf(title, sizeof title, "%.200s, N = %zu, L = %.6f", base ? base + 1 : in, r->one.nv, r->th.length);
    tr_plot_script ps;
    if ((rc = tr_tube_script_write(dir, &tp, &views, title, px, &ps, err)) == TR_OK)
        rc = tr_gnuplot_draw(dir, "tube.gp", "tube_gnuplot.log", &ps, err);
    tr_tube_picture_free(&tp);
    return rc;
}

/* Writes the tables, the summary and (with --plots) the plots of one
 * analysed component into dir, which exists (in the stage of of). Returns
 * a process status; an interrupt is 1, unreported. */
static int write_component(comp_result *r, const char *in, const char *dir, const tr_out_folder *of,
                           const cli_opts *o, const tr_clasp_report *clasp)
{
    if (r->open)
        return write_open_rope(r, in, dir, of, o, clasp);
    tr_error err = {{0}};
    const tr_analysis *an = &r->an;
    tr_report_ctx ctx = {in, r->k, r->scale, &r->th,
                         o->paper < 0 ? tr_report_is_trefoil_like(an, &r->th) : o->paper};
    /* Each table is formatted (non-zero only when memory runs out), then
     * written atomically. */
    char *t = NULL, *txt = NULL;
    int rc = TR_OK, fmt = 0;
    size_t nv = r->one.nv;
#define EMIT(name, call)                                                  \
    do {                                                                  \
        if (rc == TR_OK && !fmt) {                                        \
            if ((fmt = (call)) == 0)                                      \
                rc = write_text(dir, name, t, &err);                      \
        }                                                                 \
    } while (0)
    EMIT("curvature.csv", tr_report_curvature_csv(an, &t));
    EMIT("torsion.csv", tr_report_torsion_csv(an, &t));
    EMIT("plateaus.csv", tr_report_plateaus_csv(an, &t));
    EMIT("symmetry.csv", tr_report_symmetry_csv(an, &t));
    EMIT("contacts.csv", tr_report_contacts_csv(an, r->one.x, nv, &t));
    if (an->have_sigma) {
        EMIT("sigma.csv", tr_report_sigma_csv(an, 4000, &t));
        EMIT("fixed_points.csv", tr_report_fixed_points_csv(an, &t));
    }
    EMIT("summary.json", tr_report_summary_json(an, &ctx, &t));
#undef EMIT
    if (rc == TR_OK && !fmt && (fmt = tr_report_text(an, &ctx, &txt)) == 0) {
        fputs(txt, stdout);
        rc = write_text(dir, "report.txt", txt, &err);
    } else {
        free(txt);
    }
    if (fmt || rc == TR_ENOMEM) {
        say(of, "tightrope analyze: writing %s: out of memory\n", dir);
        return 1;
    }
    if (rc != TR_OK) { /* an output the user can fix */
        say(of, "tightrope analyze: writing %s: %s\n", dir, err.msg);
        return 2;
    }
    if (o->plots) {
        char x[1100];
        const char *shown = tr_out_folder_shown(of, dir, x, sizeof x);
        rc = draw_plots(dir, an, &err);
        if (rc != TR_OK) {
            if (rc != TR_EINTERRUPTED)
                say(of, "tightrope analyze: plots: %s\n", err.msg);
            return 1;
        }
        printf("plots: %s/{curvature_torsion,plateau_zoom,accumulated_torsion%s}.png\n", shown,
               an->have_sigma ? ",contact_map,sigma9" : "");
        rc = tr_cli_interrupted() ? tr_fail(&err, TR_EINTERRUPTED, "interrupted")
                                  : draw_tube(dir, r, in, o->tube_px ? o->tube_px : TR_TUBE_PX_DEFAULT, &err);
        if (rc == TR_OK) {
            printf("tube: %s/tube_{front,top,side,struts}.png\n", shown);
        } else if (rc == TR_EGEOMETRY) { /* a core no tube can follow: the analysis stands */
            say(of, "tightrope analyze: no tube pictures: %s; the other plots are drawn\n", err.msg);
        } else {
            if (rc != TR_EINTERRUPTED)
                say(of, "tightrope analyze: tube pictures: %s\n", err.msg);
            return 1;
        }
    }
    return 0;
}

/* The tube of radius 1 around every analysed component (scaled as they
 * were analysed), one PLY file written atomically. Returns a process status. */
static int write_mesh(const comp_result *res, int nres, const char *in, const cli_opts *o)
{
    tr_error err = {{0}};
    tr_tube_mesh m = {0};
    size_t K = o->mesh_sides ? o->mesh_sides : 16;
    int rc = TR_OK;
    for (int q = 0; q < nres && rc == TR_OK; q++)
        if ((rc = tr_tube_mesh_add(&m, res[q].one.x, res[q].one.nv, !res[q].open, 1.0, K, &err)) != TR_OK)
            fprintf(stderr, "tightrope analyze: --mesh %s: component %d of %s: %s\n", o->mesh, res[q].k, in, err.msg);
    char comment[512], *text = NULL;
    snprintf(comment, sizeof comment, "tube of radius 1 around %.400s (%s), made by tightrope analyze", in,
             o->scale ? "scaled to thickness 1" : "as given");
    if (rc == TR_OK && (rc = tr_tube_mesh_ply(&m, comment, &text)) != TR_OK)
        fprintf(stderr, "tightrope analyze: --mesh %s: out of memory\n", o->mesh);
    if (rc == TR_OK && (rc = tr_write_file_atomic(o->mesh, text, strlen(text), &err)) != TR_OK &&
        !tr_cli_interrupted()) /* (an interrupt has its own message) */
        fprintf(stderr, "tightrope analyze: --mesh %s: %s\n", o->mesh, err.msg);
    if (rc == TR_OK)
        printf("mesh: %s (%zu vertices, %zu triangles)\n", o->mesh, m.nv, m.nf);
    free(text);
    tr_tube_mesh_free(&m);
    return rc == TR_OK ? 0 : rc == TR_ENOMEM ? 1 : 2;
}

/* Options followed by a value. */
static int takes_value(const char *a)
{
    static const char *const names[] = {"--out",      "-o",          "-m",          "--plateau-eps",
                                        "--plateau-min", "--plateau-edge", "--jump-window", "--jump-at", "--sym-tol",
                                        "--strut-tol", "--contact-bin", "--power", "--mesh", "--mesh-sides",
                                        "--tube-size"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++)
        if (!strcmp(a, names[i]))
            return 1;
    return 0;
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
        } else if (!strcmp(a, "--paper") || !strcmp(a, "--no-paper")) {
            if (o.paper >= 0 && o.paper != (a[2] == 'p')) {
                fprintf(stderr, "tightrope analyze: --paper and --no-paper contradict each other\n");
                return 2;
            }
            o.paper = a[2] == 'p';
        } else if (!strcmp(a, "--no-scale")) {
            o.scale = 0;
        } else if (takes_value(a) && !v) {
            fprintf(stderr, "tightrope analyze: %s needs a value\n", a);
            return 2;
        } else if (!strcmp(a, "--out") || !strcmp(a, "-o")) {
            if (!*v) {
                fprintf(stderr, "tightrope analyze: %s needs a directory name\n", a);
                return 2;
            }
            out = v, i++;
        } else if (!strcmp(a, "-m")) {
            if (tr_arg_size(v, 1, 1000000, &o.ao.m)) {
                fprintf(stderr, "tightrope analyze: -m needs an integer from 1 to 1000000, got '%s'\n", v);
                return 2;
            }
            i++;
        } else if (!strcmp(a, "--mesh")) {
            if (!*v) {
                fprintf(stderr, "tightrope analyze: --mesh needs a file name\n");
                return 2;
            }
            o.mesh = v, i++;
        } else if (!strcmp(a, "--mesh-sides")) {
            if (tr_arg_size(v, 3, TR_TUBE_SIDES_MAX, &o.mesh_sides)) {
                fprintf(stderr, "tightrope analyze: --mesh-sides needs an integer from 3 to %d, got '%s'\n",
                        TR_TUBE_SIDES_MAX, v);
                return 2;
            }
            i++;
        } else if (!strcmp(a, "--tube-size")) {
            if (tr_arg_int(v, TR_TUBE_PX_MIN, TR_TUBE_PX_MAX, &o.tube_px)) {
                fprintf(stderr, "tightrope analyze: --tube-size needs an integer from %d to %d (pixels), got '%s'\n",
                        TR_TUBE_PX_MIN, TR_TUBE_PX_MAX, v);
                return 2;
            }
            i++;
        } else if (!strcmp(a, "--power")) {
            if (tr_arg_int(v, 1, TR_CONTACT_POWER_MAX, &o.ao.power)) {
                fprintf(stderr, "tightrope analyze: --power needs an integer from 1 to %d, got '%s'\n",
                        TR_CONTACT_POWER_MAX, v);
                return 2;
            }
            i++;
        } else if (!strcmp(a, "--plateau-min")) {
            if (tr_arg_size(v, 1, 1000000000, &o.ao.plateau_min)) {
                fprintf(stderr, "tightrope analyze: --plateau-min needs an integer >= 1 (arcs), got '%s'\n", v);
                return 2;
            }
            i++;
        } else if (!strcmp(a, "--plateau-eps")) {
            if (tr_arg_double(v, 0, 1, &d) || d == 0 || d == 1) {
                fprintf(stderr, "tightrope analyze: --plateau-eps needs a number in (0, 1), got '%s'\n", v);
                return 2;
            }
            o.ao.plateau_eps = d, i++;
        } else if (!strcmp(a, "--plateau-edge")) {
            if (tr_arg_double(v, 0, 1, &d) || d == 0 || d == 1) {
                fprintf(stderr, "tightrope analyze: --plateau-edge needs a number in (0, 1), got '%s'\n", v);
                return 2;
            }
            o.ao.plateau_edge = d, i++;
        } else if (!strcmp(a, "--sym-tol") || !strcmp(a, "--strut-tol")) {
            if (tr_arg_double(v, 0, 1, &d) || d == 0) {
                fprintf(stderr, "tightrope analyze: %s needs a number in (0, 1], got '%s'\n", a, v);
                return 2;
            }
            if (!strcmp(a, "--sym-tol"))
                o.ao.sym_tol = d;
            else
                o.strut_tol = d;
            i++;
        } else if (!strcmp(a, "--contact-bin")) {
            /* the upper and lower bounds depend on the knot's length: checked
             * per component once it is scaled */
            if (tr_arg_double(v, 0, INFINITY, &d) || d == 0) {
                fprintf(stderr, "tightrope analyze: --contact-bin needs a positive number, got '%s'\n", v);
                return 2;
            }
            o.ao.contact_bin = d, i++;
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
                fprintf(stderr, "tightrope analyze: --jump-at needs 1 to 64 comma-separated numbers, got '%s'\n", v);
                return 2;
            }
            o.ao.jump_at = o.jump_at;
            o.ao.n_jump_at = n, i++;
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "tightrope analyze: unknown option '%s' (see tightrope analyze --help)\n", a);
            return 2;
        } else if (!in) {
            in = a;
        } else {
            fprintf(stderr, "tightrope analyze: one input file only ('%s' and '%s')\n", in, a);
            return 2;
        }
    }
    if (!in) {
        fprintf(stderr, "tightrope analyze: no input curve (see tightrope analyze --help)\n");
        return 2;
    }
    if (!out) {
        fprintf(stderr, "tightrope analyze: no output directory (--out DIR)\n");
        return 2;
    }
    if (o.tube_px && !o.plots) {
        fprintf(stderr, "tightrope analyze: --tube-size needs --plots\n");
        return 2;
    }
    if (o.mesh_sides && !o.mesh) {
        fprintf(stderr, "tightrope analyze: --mesh-sides needs --mesh FILE\n");
        return 2;
    }
    /* before any computation: a run asked for plots that cannot draw them
     * has failed (it used to write the tables alone and exit 0) */
    if (o.plots && !tr_gnuplot_available()) {
        fprintf(stderr,
                "tightrope analyze: --plots needs gnuplot, which is not on PATH (Debian package gnuplot-nox)\n");
        return 2;
    }
    tr_error err = {{0}};
    if (o.mesh && tr_same_file(o.mesh, in)) {
        fprintf(stderr, "tightrope analyze: --mesh %s is the input file\n", o.mesh);
        return 2;
    }
    if (o.mesh && tr_check_writable(o.mesh, &err) != TR_OK) {
        fprintf(stderr, "tightrope analyze: --mesh: %s\n", err.msg);
        return 2;
    }
    tr_curve c;
    int rc = tr_curve_read(in, TR_FORMAT_AUTO, &c, &err);
    if (rc != TR_OK) {
        fprintf(stderr, "tightrope analyze: %s\n", err.msg);
        return rc == TR_EIO || rc == TR_EPARSE ? 2 : 1;
    }
    /* Everything about the input and the options is checked, and every
     * component analysed, before the output directory is made. */
    /* An explicit -m must leave 4 averaged vertices; the default follows
     * each component's N and length (tr_analysis_default_m, at most N/4). */
    size_t m = o.ao.m;
    int nres = c.ncomp; /* every component, closed or open */
    for (int k = 0; k < c.ncomp; k++) {
        size_t nv = tr_comp_nv(&c, k);
        if (!c.closed[k]) {
            if (nv < 4) {
                fprintf(stderr, "tightrope analyze: component %d of %s is an open rope of %zu vertices; its "
                                "profiles need at least 4\n", k, in, nv);
                tr_curve_free(&c);
                return 2;
            }
            continue;
        }
        if (m && nv / m < 4) {
            fprintf(stderr, "tightrope analyze: -m %zu leaves fewer than 4 averaged vertices on component %d of %s (%zu vertices)\n",
                    m, k, in, nv);
            tr_curve_free(&c);
            return 2;
        }
        if (o.ao.plateau_min > nv) {
            fprintf(stderr, "tightrope analyze: --plateau-min %zu exceeds the %zu vertices of component %d of %s\n",
                    o.ao.plateau_min, nv, k, in);
            tr_curve_free(&c);
            return 2;
        }
    }
    if (!nres) {
        fprintf(stderr, "tightrope analyze: %s has no component\n", in);
        tr_curve_free(&c);
        return 2;
    }
    comp_result *res = calloc((size_t)nres, sizeof *res);
    int *done = calloc((size_t)nres, sizeof *done);
    if (!res || !done) {
        fprintf(stderr, "tightrope analyze: out of memory\n");
        free(res), free(done);
        tr_curve_free(&c);
        return 1;
    }
    int status = 0, ndone = 0, optbad = 0;
    for (int k = 0, q = 0; k < c.ncomp && !optbad; k++) {
        int s = analyse_component(&c, k, in, &o, &res[q], &optbad);
        if (s == 0)
            done[q] = 1, ndone++;
        else if (s > status)
            status = s;
        q++;
    }
    if (optbad) /* an option wrong for the input: nothing is written */
        ndone = 0, status = 2;
    /* A simple clasp, two open ropes: the pieces of each (docs/physics.md 6.2) */
    tr_cli_clasp *clasp = NULL;
    if (nres == 2 && done[0] && done[1] && res[0].open && res[1].open) {
        tr_error err2 = {{0}};
        if (!(clasp = malloc(sizeof *clasp)) ||
            tr_cli_clasp_read(&res[0].rope.prof, &res[1].rope.prof, clasp, &err2) != TR_OK) {
            fprintf(stderr, "tightrope analyze: %s: the clasp's anatomy: %s\n", in,
                    clasp ? err2.msg : "out of memory");
            ndone = 0, status = 1;
        }
    }
    int comps[2] = {res[0].k, nres > 1 ? res[1].k : 0};
    /* All or nothing: every file goes into a staging folder inside out and
     * is moved into place only once all are written; an earlier run's files
     * are replaced or removed only if its record lists them unchanged, the
     * input never (out_folder.h). From here an interrupt stops gnuplot and
     * removes what this run wrote. */
    tr_out_folder of;
    int opened = 0, aborted_by = 0;
    const char *keep[1] = {in};
    if (status == 0 && ndone == nres) {
        tr_cli_catch_interrupts();
        tr_error e2 = {{0}};
        int rc2 = tr_out_folder_open(&of, out, ANALYZE_RECORD, "tightrope analyze", &e2);
        if (rc2 != TR_OK) {
            fprintf(stderr, "tightrope analyze: %s\n", e2.msg);
            status = rc2 == TR_ENOMEM ? 1 : 2;
        }
        opened = rc2 == TR_OK;
    }
    for (int q = 0; q < nres && opened && status == 0 && !tr_cli_interrupted(); q++) {
        char dir[4400];
        const char *stage = tr_out_folder_stage(&of);
        int len = c.ncomp > 1 ? snprintf(dir, sizeof dir, "%s/comp%d", stage, res[q].k)
                              : snprintf(dir, sizeof dir, "%s", stage);
        if (len < 0 || (size_t)len >= sizeof dir) {
            fprintf(stderr, "tightrope analyze: output directory name too long: %s\n", out);
            status = 2;
            break;
        }
        if (c.ncomp > 1 && mkdir(dir, 0777) != 0) {
            say(&of, "tightrope analyze: cannot create directory %s: %s\n", dir, strerror(errno));
            status = 2;
            break;
        }
        tr_clasp_report view;
        if (clasp)
            view = tr_cli_clasp_view(clasp, q, comps);
        status = write_component(&res[q], in, dir, &of, &o, clasp ? &view : NULL);
    }
    if (opened && status == 0 && !tr_cli_interrupted()) {
        tr_error e2 = {{0}};
        int rc2 = tr_out_folder_commit(&of, keep, 1, &e2);
        if (rc2 != TR_OK) {
            fprintf(stderr, "tightrope analyze: %s\n", e2.msg);
            status = rc2 == TR_ENOMEM ? 1 : 2;
        } else if (o.mesh && tr_out_folder_holds(&of, o.mesh)) {
            /* the mesh would replace a file just written */
            fprintf(stderr, "tightrope analyze: --mesh %s is one of the files analyze writes in %s\n", o.mesh, out);
            status = 2;
        } else if (o.mesh) { /* last: a failure can still undo the folder */
            status = write_mesh(res, nres, in, &o);
        }
    }
    if (opened) {
        /* an interrupt once every file is in place comes too late to lose them */
        if (status == 0 && (!tr_cli_interrupted() || of.committed)) {
            tr_out_folder_finish(&of, keep, 1);
        } else {
            aborted_by = tr_cli_interrupted();
            tr_out_folder_abort(&of);
        }
    }
    for (int q = 0; q < nres; q++)
        if (done[q])
            comp_result_free(&res[q]);
    free(res), free(done), free(clasp);
    tr_curve_free(&c);
    if (aborted_by) {
        /* ended as the signal would have ended it, so that a shell loop
         * running analyze stops too */
        fprintf(stderr, "tightrope analyze: interrupted; nothing written to %s\n", out);
        signal(aborted_by, SIG_DFL);
        raise(aborted_by);
        return 1;
    }
    return status;
}
