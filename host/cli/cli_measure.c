/* tightrope measure FILE... [--json] [--struts OUT] [--per-component] [--strut-tol REL]
 *                           [--kkt] [--kkt-band REL] [--kkt-forces OUT]
 *                           [--contacts segment|vertex] [--invariants]
 *
 * Length, MinRad, shortest strut (dcsd), thickness, ropelength and the
 * paper's L_p, L_c, L_a of each curve file (thickness.h), and with --kkt
 * the KKT certificate of its tightness (kkt.h). Every file is read
 * before anything is measured or written, so bad input prints the reader's
 * one line, exits 2 and leaves no --struts file behind. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/cli_args.h"
#include "cli/measure_identify.h"
#include "cli/measure_invariants.h"
#include "cli/measure_vertex.h"
#include "curve/curve_io.h"
#include "util/json.h"
#include "oracle/kkt.h"
#include "util/text_file.h"
#include "oracle/thickness.h"

/* Struts within this relative distance of the shortest go to --struts:
 * the contact set of a knot tight to a few 1e-4 (TightKnot at N ~ 400). */
#define DEFAULT_STRUT_TOL 1e-3

static void usage(FILE *out)
{
    fprintf(out,
            "usage: tightrope measure FILE... [--json] [--per-component] [--struts OUT] [--strut-tol REL]\n"
            "                         [--kkt] [--kkt-band REL] [--kkt-forces OUT]\n"
            "  FILE            curve file (.vect, .tsv, KnotPlot x y z list)\n"
            "  --json          one JSON object per file (an array if several)\n"
            "  --per-component also measure each component on its own (always in --json)\n"
            "  --struts OUT    write the struts within REL of the shortest, and the MinRad\n"
            "                  vertex, in octrope's STRUTS format (one FILE only)\n"
            "  --strut-tol REL relative tolerance for --struts (default %g)\n"
            "  --kkt           also certify tightness: the KKT residual |g - J^T y| / |g|, the\n"
            "                  part of the rope's tension no compressive strut or curvature\n"
            "                  limit holds (0: critical, 1: nothing holds it)\n"
            "  --kkt-band REL  constraints within REL of their bound may hold (default %g)\n"
            "  --kkt-forces OUT  write, per vertex, the tension and the part of it nothing\n"
            "                  holds (CSV; one FILE only): where a curve is not critical\n"
            "  --contacts M    segment: Rawdon's thickness only (default); vertex: also\n"
            "                  SP-FEM's vertex model (vertices at least 2R apart that are\n"
            "                  K = ceil(pi R / e) or more apart along the rope); not with --kkt\n"
            "  --invariants    also the knot type: Alexander polynomial (t^-h .. t^h, Delta(1) = 1),\n"
            "                  determinant and crossings of a generic projection (one closed component)\n"
            "  --identify [NAME]  only the type: whether the curve's invariants (a knot's Alexander\n"
            "                  polynomial, determinant and signature up to sign, a link's components\n"
            "                  and linking numbers) are NAME's (exit 0, else 1), and the table's knots\n"
            "                  or links with the same invariants (without NAME: exit 1 when there are\n"
            "                  none); one FILE; --identify=NAME where a file is called NAME\n",
            DEFAULT_STRUT_TOL, TR_KKT_DEFAULT_BAND);
}

static void json_num(tr_text *t, const char *key, double v, int comma)
{
    tr_text_printf(t, "\"%s\": ", key);
    tr_json_number(t, "%.17g", v);
    tr_text_printf(t, "%s", comma ? ", " : "");
}

static void json_fields(tr_text *t, const tr_thickness *m)
{
    tr_text_printf(t, "\"vertices\": %zu, ", m->vertices);
    json_num(t, "length", m->length, 1);
    json_num(t, "minrad", m->minrad, 1);
    json_num(t, "dcsd", m->dcsd, 1);
    json_num(t, "thickness", m->thickness, 1);
    json_num(t, "ropelength", m->ropelength, 1);
    json_num(t, "L_p", m->L_p, 1);
    json_num(t, "L_c", m->L_c, 1);
    json_num(t, "L_a", m->L_a, 1);
    tr_text_printf(t, "\"minrad_vertex\": %zu", m->minrad_vertex);
    if (isfinite(m->dcsd))
        tr_text_printf(t, ", \"shortest_strut\": {\"edges\": [%zu, %zu], \"positions\": [%.17g, %.17g], \"length\": %.17g}",
                m->shortest.ei, m->shortest.ej, m->shortest.si, m->shortest.sj, m->shortest.dist);
}

static void json_kkt(tr_text *t, const tr_kkt *k, double band)
{
    tr_text_printf(t, ", \"kkt\": {");
    json_num(t, "residual", k->residual, 1);
    json_num(t, "band", band, 1);
    json_num(t, "radius", k->radius, 1);
    json_num(t, "tension", k->force, 1);
    tr_text_printf(t, "\"strut_rows\": %zu, \"strut_active\": %zu, \"minrad_rows\": %zu, \"minrad_active\": %zu, ",
                   k->strut_rows, k->strut_active, k->minrad_rows, k->minrad_active);
    json_num(t, "strut_force_max", k->strut_force_max, 1);
    json_num(t, "optimality", k->optimality, 1);
    tr_text_printf(t, "\"converged\": %s}", k->converged ? "true" : "false");
}

static void table_kkt(tr_text *t, const tr_kkt *k, double band)
{
    tr_text_printf(t, "KKT residual %.6e (band %g, radius %.15g: %zu/%zu struts and %zu/%zu MinRad rows hold; %s)\n",
                   k->residual, band, k->radius, k->strut_active, k->strut_rows, k->minrad_active, k->minrad_rows,
                   k->converged ? "multipliers optimal" : "an upper bound: multipliers not optimal");
}

/* One row per vertex: where the tension is and what of it nothing holds. */
static int write_kkt_forces(const char *path, const char *file, const tr_curve *c, const double *g,
                            const double *r, tr_error *err)
{
    tr_text t = {0};
    tr_text_printf(&t, "# tightrope measure --kkt-forces %s: tension g and unresolved force r = g - J^T y per vertex\n",
                   file);
    tr_text_printf(&t, "component,vertex,tension,unresolved,unresolved_x,unresolved_y,unresolved_z\n");
    for (int k = 0; k < c->ncomp; k++)
        for (size_t i = c->start[k]; i < c->start[k + 1]; i++) {
            const double *gi = g + 3 * i, *ri = r + 3 * i;
            tr_text_printf(&t, "%d,%zu,%.10e,%.10e,%.10e,%.10e,%.10e\n", k, i - c->start[k],
                           sqrt(gi[0] * gi[0] + gi[1] * gi[1] + gi[2] * gi[2]),
                           sqrt(ri[0] * ri[0] + ri[1] * ri[1] + ri[2] * ri[2]), ri[0], ri[1], ri[2]);
        }
    return tr_text_write_atomic(&t, path, err);
}

static void table_row(tr_text *t, const char *label, const tr_thickness *m)
{
    tr_text_printf(t, "%-10s %9zu %22.15g %22.15g %22.15g %22.15g %22.15g %22.15g %22.15g %22.15g\n", label,
            m->vertices, m->length, m->minrad, m->dcsd, m->thickness, m->ropelength, m->L_p, m->L_c,
            m->L_a);
}

/* octrope_strutfile_write's layout ("STRUTS", counts, then one line per
 * strut: component[0] component[1] lead_vert[0] lead_vert[1] position[0]
 * position[1] length compression, then one line per MinRad location:
 * component vertex mr compression), with %.17g instead of %16g so the
 * numbers survive the round trip. lead_vert is the edge's first vertex
 * within its component; compression is 0 (we measure, we do not solve). */
static int write_struts(const char *path, const tr_curve *c, const tr_thickness *m,
                        const tr_strut_list *sl, tr_error *err)
{
    tr_text t = {0};
    int have_mr = isfinite(m->minrad);
    tr_text_printf(&t, "STRUTS \n%zu %d \n", sl->n, have_mr ? 1 : 0);
    /* Global edge -> (component, first vertex in the component). */
    for (size_t i = 0; i < sl->n; i++) {
        const tr_strut *s = &sl->s[i];
        size_t e[2] = {s->ei, s->ej};
        int comp[2];
        size_t lead[2];
        for (int q = 0; q < 2; q++) {
            size_t off = 0;
            int k = 0;
            while (k + 1 < c->ncomp && e[q] >= off + tr_comp_ne(c, k)) {
                off += tr_comp_ne(c, k);
                k++;
            }
            comp[q] = k;
            lead[q] = e[q] - off;
        }
        tr_text_printf(&t, "%d %d %zu %zu %.17g %.17g %.17g %.17g\n", comp[0], comp[1], lead[0], lead[1], s->si,
                s->sj, s->dist, 0.0);
    }
    if (have_mr) {
        int k = tr_curve_comp_of(c, m->minrad_vertex);
        tr_text_printf(&t, "%d %zu %.17g %.17g \n", k, m->minrad_vertex - c->start[k], m->minrad, 0.0);
    }
    return tr_text_write_atomic(&t, path, err);
}

int tr_cmd_measure(int argc, char **argv)
{
    int json = 0, per_comp = 0, kkt = 0, vertex_contacts = 0, invariants = 0, identify = 0;
    const char *identify_name = NULL;
    tr_kkt_params kp;
    tr_kkt_params_default(&kp);
    const char *struts_path = NULL, *forces_path = NULL;
    double strut_tol = DEFAULT_STRUT_TOL;
    const char **files = calloc((size_t)argc + 1, sizeof *files);
    int nfiles = 0;
    if (!files) {
        fprintf(stderr, "tightrope measure: out of memory\n");
        return 1;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            free(files);
            return 0;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--per-component")) {
            per_comp = 1;
        } else if (!strcmp(a, "--struts") && i + 1 < argc) {
            struts_path = argv[++i];
        } else if (!strcmp(a, "--strut-tol") && i + 1 < argc) {
            if (tr_arg_double(argv[++i], 0.0, HUGE_VAL, &strut_tol)) {
                fprintf(stderr, "tightrope measure: --strut-tol wants a number >= 0, got '%s'\n", argv[i]);
                free(files);
                return 2;
            }
        } else if (!strcmp(a, "--kkt-forces") && i + 1 < argc) {
            kkt = 1;
            forces_path = argv[++i];
        } else if (!strcmp(a, "--kkt")) {
            kkt = 1;
        } else if (!strcmp(a, "--kkt-band") && i + 1 < argc) {
            kkt = 1;
            if (tr_arg_double(argv[++i], 0.0, 1.0, &kp.band)) {
                fprintf(stderr, "tightrope measure: --kkt-band wants a number in [0, 1], got '%s'\n", argv[i]);
                free(files);
                return 2;
            }
        } else if (!strcmp(a, "--invariants")) {
            invariants = 1;
        } else if (!strcmp(a, "--identify") || !strncmp(a, "--identify=", 11)) {
            /* NAME is the next argument unless that is an option or an
             * existing file (measure FILE --identify, measure --identify
             * FILE); --identify=NAME says it outright */
            identify = 1;
            if (a[10] == '=') {
                identify_name = a + 11;
            } else if (i + 1 < argc && argv[i + 1][0] != '-') {
                FILE *probe = fopen(argv[i + 1], "rb");
                if (probe)
                    fclose(probe);
                else
                    identify_name = argv[++i];
            }
        } else if (!strcmp(a, "--contacts") && i + 1 < argc) {
            const char *m = argv[++i];
            if (strcmp(m, "segment") && strcmp(m, "vertex")) {
                fprintf(stderr, "tightrope measure: --contacts wants segment or vertex, got '%s'\n", m);
                free(files);
                return 2;
            }
            vertex_contacts = !strcmp(m, "vertex");
        } else if (a[0] == '-' && a[1] == '-') {
            fprintf(stderr, "tightrope measure: unknown or incomplete option '%s' (see tightrope measure --help)\n", a);
            free(files);
            return 2;
        } else {
            files[nfiles++] = a;
        }
    }
    if (vertex_contacts && kkt) {
        /* The certificate's constraints are Rawdon's struts; the vertex
         * model's multipliers are not defined here. */
        fprintf(stderr, "tightrope measure: --contacts vertex has no KKT certificate (--kkt, --kkt-band, "
                        "--kkt-forces are Rawdon's)\n");
        free(files);
        return 2;
    }
    if (nfiles == 0 || ((struts_path || forces_path) && nfiles != 1)) {
        fprintf(stderr, nfiles ? "tightrope measure: --struts and --kkt-forces take exactly one FILE\n"
                               : "tightrope measure: no FILE given\n");
        usage(stderr);
        free(files);
        return 2;
    }

    if (identify) {
        if (nfiles != 1 || json || per_comp || kkt || vertex_contacts || invariants || struts_path) {
            fprintf(stderr, nfiles != 1 ? "tightrope measure: --identify takes exactly one FILE\n"
                                        : "tightrope measure: --identify goes alone (no other option)\n");
            free(files);
            return 2;
        }
        tr_error rerr;
        tr_curve c;
        int rc = tr_curve_read(files[0], TR_FORMAT_AUTO, &c, &rerr);
        if (rc) {
            fprintf(stderr, "tightrope measure: %s\n", rerr.msg);
            free(files);
            return rc == TR_ENOMEM ? 1 : 2;
        }
        int st = tr_measure_identify(files[0], &c, identify_name);
        tr_curve_free(&c);
        free(files);
        return st;
    }

    /* An output over an input (by identity: ./k.vect, a hard or a symbolic
     * link count too) would destroy what is measured; two outputs over each
     * other would keep one. */
    const char *outs[2] = {struts_path, forces_path}, *optname[2] = {"--struts", "--kkt-forces"};
    for (int o = 0; o < 2; o++) {
        if (!outs[o])
            continue;
        for (int f = 0; f < nfiles; f++)
            if (tr_same_file(outs[o], files[f]) || !strcmp(outs[o], files[f])) {
                fprintf(stderr, "tightrope measure: %s %s is the input %s; write it elsewhere\n", optname[o],
                        outs[o], files[f]);
                free(files);
                return 2;
            }
    }
    if (struts_path && forces_path && (tr_same_file(struts_path, forces_path) || !strcmp(struts_path, forces_path))) {
        fprintf(stderr, "tightrope measure: --struts and --kkt-forces are both %s\n", struts_path);
        free(files);
        return 2;
    }

    /* Read everything first: a bad file stops the run before any output. */
    tr_curve *curves = calloc((size_t)nfiles, sizeof *curves);
    if (!curves) {
        fprintf(stderr, "tightrope measure: out of memory\n");
        free(files);
        return 1;
    }
    tr_error err;
    int status = 0, nread = 0;
    for (; nread < nfiles; nread++) {
        int rc = tr_curve_read(files[nread], TR_FORMAT_AUTO, &curves[nread], &err);
        if (rc) {
            fprintf(stderr, "tightrope measure: %s\n", err.msg);
            status = rc == TR_ENOMEM ? 1 : 2; /* cli.h: out of memory is 1 */
            break;
        }
    }

    tr_text out = {0};
    tr_strut_list sl = {0};
    if (json && nfiles > 1)
        tr_text_printf(&out, "[\n");
    for (int f = 0; f < nfiles && status == 0; f++) {
        const tr_curve *c = &curves[f];
        tr_thickness m;
        tr_thickness_opts opts = {.strut_rel_tol = strut_tol};
        if (tr_thickness_measure(c, &opts, &m, struts_path ? &sl : NULL, &err)) {
            fprintf(stderr, "tightrope measure: %s: %s\n", files[f], err.msg);
            status = 2;
            break;
        }
        tr_kkt kr;
        double *kg = NULL, *kres = NULL;
        if (forces_path && (!(kg = malloc(3 * c->nv * sizeof *kg)) || !(kres = malloc(3 * c->nv * sizeof *kres)))) {
            free(kg);
            fprintf(stderr, "tightrope measure: out of memory\n");
            status = 1;
            break;
        }
        if (kkt && tr_kkt_certify_forces(c, &kp, &kr, kg, kres, &err)) {
            fprintf(stderr, "tightrope measure: %s: %s\n", files[f], err.msg);
            free(kg);
            free(kres);
            status = 2;
            break;
        }
        int frc = forces_path ? write_kkt_forces(forces_path, files[f], c, kg, kres, &err) : TR_OK;
        free(kg);
        free(kres);
        if (frc) {
            fprintf(stderr, "tightrope measure: %s\n", err.msg);
            status = 2; /* cannot write an output: like bad input, see cli.h */
            break;
        }
        tr_thickness *pc = NULL;
        if (json || per_comp) {
            pc = calloc((size_t)c->ncomp, sizeof *pc);
            if (!pc) {
                fprintf(stderr, "tightrope measure: out of memory\n");
                status = 1;
                break;
            }
            for (int k = 0; k < c->ncomp && status == 0; k++) {
                if (c->ncomp == 1) {
                    pc[k] = m;
                } else if (tr_thickness_measure_component(c, k, &pc[k], &err)) {
                    fprintf(stderr, "tightrope measure: %s: component %d: %s\n", files[f], k, err.msg);
                    status = 2;
                }
            }
        }
        if (status == 0 && json) {
            tr_text_printf(&out, "%s{\"file\": ", nfiles > 1 ? "  " : "");
            tr_json_string(&out, files[f]);
            tr_text_printf(&out, ", \"components\": %d, ", c->ncomp);
            json_fields(&out, &m);
            if (vertex_contacts && (status = tr_measure_vertex_append(&out, c, &m, 1, &err))) {
                fprintf(stderr, "tightrope measure: %s: %s\n", files[f], err.msg);
                status = status == TR_ENOMEM ? 1 : 2;
                free(pc);
                break;
            }
            if (kkt)
                json_kkt(&out, &kr, kp.band);
            if (invariants && (status = tr_measure_invariants_append(&out, c, 1, &err))) {
                fprintf(stderr, "tightrope measure: %s: %s\n", files[f], err.msg);
                status = status == TR_ENOMEM ? 1 : 2;
                free(pc);
                break;
            }
            tr_text_printf(&out, ", \"per_component\": [");
            for (int k = 0; k < c->ncomp; k++) {
                tr_text_printf(&out, "%s{\"component\": %d, \"closed\": %s, ", k ? ", " : "", k,
                        c->closed[k] ? "true" : "false");
                json_fields(&out, &pc[k]);
                tr_text_printf(&out, "}");
            }
            tr_text_printf(&out, "]}%s\n", (nfiles > 1 && f + 1 < nfiles) ? "," : "");
        } else if (status == 0) {
            tr_text_printf(&out, "%s: %d component%s\n", files[f], c->ncomp, c->ncomp == 1 ? "" : "s");
            tr_text_printf(&out, "%-10s %9s %22s %22s %22s %22s %22s %22s %22s %22s\n", "", "vertices", "length",
                    "minrad", "dcsd", "thickness", "ropelength", "L_p", "L_c", "L_a");
            table_row(&out, "curve", &m);
            for (int k = 0; per_comp && k < c->ncomp; k++) {
                char label[32];
                snprintf(label, sizeof label, "comp %d", k);
                table_row(&out, label, &pc[k]);
            }
            if (vertex_contacts && (status = tr_measure_vertex_append(&out, c, &m, 0, &err))) {
                fprintf(stderr, "tightrope measure: %s: %s\n", files[f], err.msg);
                status = status == TR_ENOMEM ? 1 : 2;
                free(pc);
                break;
            }
            if (kkt)
                table_kkt(&out, &kr, kp.band);
            if (invariants && (status = tr_measure_invariants_append(&out, c, 0, &err))) {
                fprintf(stderr, "tightrope measure: %s: %s\n", files[f], err.msg);
                status = status == TR_ENOMEM ? 1 : 2;
                free(pc);
                break;
            }
            if (f + 1 < nfiles)
                tr_text_printf(&out, "\n");
        }
        free(pc);
        if (status == 0 && struts_path && write_struts(struts_path, c, &m, &sl, &err)) {
            fprintf(stderr, "tightrope measure: %s\n", err.msg);
            status = 2; /* cannot write an output: like bad input, see cli.h */
        }
    }
    if (status == 0 && json && nfiles > 1)
        tr_text_printf(&out, "]\n");
    if (status == 0 && out.oom) {
        fprintf(stderr, "tightrope measure: out of memory formatting the output\n");
        status = 1;
    }
    if (status == 0)
        fwrite(out.s, 1, out.n, stdout);
    free(out.s);
    tr_strut_list_free(&sl);
    for (int f = 0; f < nread && f < nfiles; f++)
        tr_curve_free(&curves[f]);
    free(curves);
    free(files);
    return status;
}
