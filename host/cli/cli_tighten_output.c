/* What a tighten leaves (cli_tighten.h): the output file with its
 * certificate and the command line in comments, and the summary on stdout
 * (lines, or JSON with --json). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli/cli_tighten.h"
#include "curve/curve_io.h"
#include "util/json.h"
#include "util/text_file.h"

static void json_num(const char *key, double v, int comma)
{
    if (isfinite(v))
        printf("  \"%s\": %.17g%s\n", key, v, comma ? "," : "");
    else
        printf("  \"%s\": null%s\n", key, comma ? "," : "");
}

static void json_str(const char *key, const char *v, int comma)
{
    printf("  \"%s\": ", key);
    tr_json_fputs(stdout, v);
    printf("%s\n", comma ? "," : "");
}

/* The model a vertex-contact run held, in one line (K: the vertex oracle's
 * exclusion for the written curve). */
static void vertex_model_line(tr_text *t, const tr_tighten_result *r)
{
    tr_text_printf(t, "contacts: vertex (SP-FEM), K = %zu: vertices on different components or >= K apart along "
                      "one at least 2 apart, MinRad >= 1; the first-order engine, polish and Rawdon's KKT "
                      "certificate do not apply\n", r->vt.exclusion);
}

/* A vertex-contact run's measures: the model's by the vertex oracle on the
 * written curve (tr_tighten measured it), then Rawdon's of the same curve,
 * whose closest segments lie a sag e^2/8 inside 2. */
static void vertex_comments(tr_text *t, const tr_tighten_result *r)
{
    const tr_vertex_thickness *v = &r->vt;
    const tr_thickness *th = &r->th;
    vertex_model_line(t, r);
    tr_text_printf(t, "N %zu\nlength %.17g\nMinRad %.17g\nvertex_dmin %.17g\nthickness %.17g (vertex model)\n"
                      "ropelength %.17g (vertex model)\n", v->vertices, v->length, v->minrad, v->vertex_dmin,
                   v->thickness, v->ropelength);
    tr_text_printf(t, "rawdon: dcsd %.17g thickness %.17g ropelength %.17g\n", th->dcsd, th->thickness,
                   th->ropelength);
    tr_text_printf(t, "steps %ld (second-order)\nstop %s\nrescaled to vertex-model thickness 1\n", r->steps,
                   tr_stop_reason_name(r->stop));
    tr_text_printf(t, "%s\n", r->type_line);
    tr_text_printf(t, "kkt_residual not computed (Rawdon's certificate; not the vertex model's)\n");
    const tr_engine_progress *p = &r->progress;
    tr_text_printf(t, "newton %s%s: vertex-model ropelength %.9f -> %.9f in %.2f s, %d steps%s%s%s\n",
                   p->newton_ran > 0 ? "accepted" : "rejected",
                   r->stop == TR_STOP_SOLVED ? (r->vertex_converged ? " converged" : " settled") : "",
                   p->newton_before, p->newton_after, p->newton_seconds, p->newton_iters, r->vertex_why ? " (" : "",
                   r->vertex_why ? r->vertex_why : "", r->vertex_why ? ")" : "");
    if (r->shift[0] != 0 || r->shift[1] != 0 || r->shift[2] != 0)
        tr_text_printf(t, "centred: the start was moved by (%.17g, %.17g, %.17g) to be tightened about the "
                          "origin\n", 0.0 - r->shift[0], 0.0 - r->shift[1], 0.0 - r->shift[2]);
}

/* Writes r's curve to OUT with its certificate and the command line in
 * comments. */
int tr_cli_tighten_write(const tr_cli_tighten *t, const tr_tighten_result *r, int argc, char **argv, tr_error *err)
{
    const tr_engine_progress *p = &r->progress;
    const tr_thickness *th = &r->th;
    const tr_kkt *kr = &r->kkt;
    tr_text cm = {0};
    tr_text_printf(&cm, "tightened by tightrope %s on %s\n", TIGHTROPE_VERSION, r->device);
    tr_text_printf(&cm, "command:");
    for (int i = 0; i < argc; i++)
        tr_text_printf(&cm, " %s", argv[i]);
    tr_text_printf(&cm, "\n");
    if (r->vertex) {
        vertex_comments(&cm, r);
        goto write;
    }
    tr_text_printf(&cm, "N %zu\nlength %.17g\nMinRad %.17g\ndcsd %.17g\nthickness %.17g\nropelength %.17g\n",
            th->vertices, th->length, th->minrad, th->dcsd, th->thickness, th->ropelength);
    if (isfinite(r->residual))
        tr_text_printf(&cm, "residual %.6g\n", r->residual);
    else
        tr_text_printf(&cm, "residual not computed (no step taken)\n");
    tr_text_printf(&cm, "steps %ld\nstop %s\n%s", r->steps, tr_stop_reason_name(r->stop),
            r->rescaled ? "rescaled to thickness 1\n" : "");
    tr_text_printf(&cm, "%s\n", r->type_line);
    if (r->certified)
        tr_text_printf(&cm, "kkt_residual %.6e (band %g: %zu/%zu struts, %zu/%zu MinRad rows hold%s)\n", kr->residual,
                       TR_KKT_DEFAULT_BAND, kr->strut_active, kr->strut_rows, kr->minrad_active, kr->minrad_rows,
                       kr->converged ? "" : "; an upper bound");
    else
        tr_text_printf(&cm, "kkt_residual not computed (%s)\n", r->stop == TR_STOP_SIGNAL ? "interrupted"
                       : t->opt.kkt == 0 ? "--no-kkt" : "N above the default limit; --kkt");
    if (p->polished && !p->newton_ran)
        tr_text_printf(&cm, "polish %s: ropelength %.9f -> %.9f in %.2f s%s%s%s\n", p->polished > 0 ? "accepted" : "rejected",
                p->polish_before, p->polish_after, p->polish_seconds, p->polish_why ? " (" : "",
                p->polish_why ? p->polish_why : "", p->polish_why ? ")" : "");
    if (p->newton_ran)
        tr_text_printf(&cm, "newton %s: ropelength %.9f -> %.9f in %.2f s, %d steps\n",
                       p->newton_ran > 0 ? "accepted" : "rejected", p->newton_before, p->newton_after,
                       p->newton_seconds, p->newton_iters);
    if (r->tries > 1)
        tr_text_printf(&cm, "tries %d, seed %ld: the shortest was road %d\n", r->tries, r->seed, r->road);
    if (r->shift[0] != 0 || r->shift[1] != 0 || r->shift[2] != 0)
        tr_text_printf(&cm, "centred: the start was moved by (%.17g, %.17g, %.17g) to be tightened about the "
                            "origin\n", 0.0 - r->shift[0], 0.0 - r->shift[1], 0.0 - r->shift[2]);
write:;
    char *comments = tr_text_take(&cm, NULL);
    if (!comments)
        return tr_fail(err, TR_ENOMEM, "out of memory");
    int rc = tr_curve_write(t->out, TR_FORMAT_AUTO, &r->curve, comments, err);
    free(comments);
    return rc;
}

/* Prints the summary of the run on stdout: JSON with --json, else lines. */
void tr_cli_tighten_summary(const tr_cli_tighten *t, const tr_tighten_result *r)
{
    const tr_engine_progress *p = &r->progress;
    const tr_thickness *th = &r->th;
    const tr_kkt *kr = &r->kkt;
    if (t->json) {
        printf("{\n");
        json_str("output", t->out, 1);
        json_str("device", r->device, 1);
        if (r->vertex) {
            /* the model's figures below; Rawdon's of the same curve here
             * (a Rawdon run's summary is as it was: readers key on it) */
            json_str("contacts", "vertex", 1);
            printf("  \"exclusion\": %zu,\n", r->vt.exclusion);
            json_num("vertex_dmin", r->vt.vertex_dmin, 1);
            json_num("rawdon_thickness", th->thickness, 1);
            json_num("rawdon_ropelength", th->ropelength, 1);
        }
        json_str("stop", tr_stop_reason_name(r->stop), 1);
        printf("  \"N\": %zu,\n  \"steps\": %ld,\n  \"rejected\": %ld,\n", th->vertices, r->steps, r->rejected);
        json_num("length", th->length, 1);
        json_num("minrad", th->minrad, 1);
        json_num("dcsd", th->dcsd, 1);
        json_num("thickness", r->thickness, 1);
        json_num("ropelength", r->ropelength, 1);
        json_num("residual", r->residual, 1);
        json_num("kkt_residual", r->kkt_residual, 1);
        if (r->certified)
            printf("  \"kkt_converged\": %s,\n", kr->converged ? "true" : "false");
        printf("  \"type_checked\": %s,\n", r->type_checked ? "true" : "false");
        json_num("elapsed_s", r->elapsed, 1);
        json_num("steps_per_s", r->steps_per_s, 0);
        printf("}\n");
        return;
    }
    if (r->vertex) {
        const tr_vertex_thickness *v = &r->vt;
        printf("%s: N %zu  ropelength %.9f in the vertex model  (length %.9f, thickness %.9f, MinRad %.9f, "
               "vertex_dmin %.9f)\n", t->out, v->vertices, v->ropelength, v->length, v->thickness, v->minrad,
               v->vertex_dmin);
        printf("  contacts: vertex (SP-FEM), K = %zu; the first-order engine, polish and Rawdon's KKT certificate "
               "do not apply\n", v->exclusion);
        printf("  Rawdon's model, the same curve: ropelength %.9f (thickness %.9f, dcsd %.9f)\n", th->ropelength,
               th->thickness, th->dcsd);
        printf("  %ld second-order steps in %.1f s, stopped: %s\n", r->steps, r->elapsed,
               tr_stop_reason_name(r->stop));
        printf("  %s\n", r->type_line);
        printf("  newton %s: vertex-model ropelength %.9f -> %.9f in %.1f s, %d steps\n",
               p->newton_ran > 0 ? "accepted" : "rejected", p->newton_before, p->newton_after, p->newton_seconds,
               p->newton_iters);
        return;
    }
    printf("%s: N %zu  ropelength %.6f  (length %.6f, thickness %.9f, MinRad %.9f, dcsd %.9f)\n", t->out,
           th->vertices, th->ropelength, th->length, th->thickness, th->minrad, th->dcsd);
    char res[32] = "not computed";
    if (isfinite(r->residual))
        snprintf(res, sizeof res, "%.2e", r->residual);
    printf("  %ld steps in %.1f s, residual %s, stopped: %s\n", r->steps, r->elapsed, res,
           tr_stop_reason_name(r->stop));
    if (r->certified)
        printf("  KKT residual %.2e (%zu/%zu struts and %zu/%zu MinRad rows hold the tension%s)\n", kr->residual,
               kr->strut_active, kr->strut_rows, kr->minrad_active, kr->minrad_rows,
               kr->converged ? "" : "; an upper bound");
    printf("  %s\n", r->type_line);
    if (p->polished && !p->newton_ran)
        printf("  polish %s: ropelength %.6f -> %.6f in %.1f s%s%s%s\n", p->polished > 0 ? "accepted" : "rejected",
               p->polish_before, p->polish_after, p->polish_seconds, p->polish_why ? " (" : "",
               p->polish_why ? p->polish_why : "", p->polish_why ? ")" : "");
    if (p->newton_ran)
        printf("  newton %s: ropelength %.9f -> %.9f in %.1f s, %d steps\n", p->newton_ran > 0 ? "accepted" : "rejected",
               p->newton_before, p->newton_after, p->newton_seconds, p->newton_iters);
}

/* The report batch reads: what the summary prints, as numbers. */
void tr_cli_tighten_report(const tr_tighten_result *r, tr_tighten_report *rep)
{
    *rep = (tr_tighten_report){.written = 1,
                               .interrupted = r->interrupted,
                               .stop = tr_stop_reason_name(r->stop),
                               .n = r->th.vertices,
                               .ropelength = r->ropelength,
                               .thickness = r->thickness,
                               .minrad = r->minrad,
                               .dcsd = r->dcsd,
                               .kkt_residual = r->kkt_residual,
                               .elapsed = r->elapsed,
                               .steps = r->steps,
                               .tries = r->tries,
                               .seed = r->seed,
                               .road = r->road,
                               .type_checked = r->type_checked};
}
