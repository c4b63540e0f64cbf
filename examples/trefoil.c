/* Tightrope's C API in one page: make a trefoil, tighten it for a few
 * seconds, measure and certify the result, print it.
 *
 *   cc trefoil.c $(pkg-config --cflags --libs tightrope) -o trefoil
 *   ./trefoil [SECONDS [N]]      (default 5 s, N = 200)
 *
 * Exit status 0 when the tight trefoil's ropelength lies between the ideal
 * trefoil's 32.7429 (Przybyl & Pieranski; no rope is shorter) and the start's. */
#include <stdio.h>
#include <stdlib.h>

#include <tightrope/tightrope.h>

static void progress(const tightrope_progress *p, void *user)
{
    (void)user;
    fprintf(stderr, "\rN %zu  ropelength %.6f  %.1f s   ", p->n, p->ropelength, p->elapsed);
}

int main(int argc, char **argv)
{
    double seconds = argc > 1 ? atof(argv[1]) : 5.0;
    size_t n = argc > 2 ? (size_t)atol(argv[2]) : 200;
    tightrope_error err;
    tightrope_curve *start = NULL, *tight = NULL;

    printf("tightrope %s\n", tightrope_version());
    if (tightrope_make("trefoil", n, &start, &err)) {
        fprintf(stderr, "make: %s\n", err.message);
        return 1;
    }
    tightrope_measurement before, after;
    if (tightrope_measure(start, -1, &before, &err)) {
        fprintf(stderr, "measure: %s\n", err.message);
        return 1;
    }
    printf("start: %zu vertices, ropelength %.6f\n", before.vertices, before.ropelength);

    tightrope_tighten_options opt;
    tightrope_tighten_options_init(&opt);
    opt.time_limit = seconds;
    opt.progress = progress;
    tightrope_tighten_result res;
    if (tightrope_tighten(start, &opt, &tight, &res, &err)) {
        fprintf(stderr, "tighten: %s (%s)\n", err.message, tightrope_strerror(err.status));
        tightrope_curve_free(start);
        return 1;
    }
    fprintf(stderr, "\n");
    tightrope_kkt kkt;
    if (tightrope_measure(tight, -1, &after, &err) || tightrope_certify(tight, 0.0, &kkt, NULL, NULL, &err)) {
        fprintf(stderr, "measure: %s\n", err.message);
        return 1;
    }
    printf("tight: %zu vertices, ropelength %.6f (thickness %.9f), KKT residual %.3e, stopped: %s, %.1f s on %s\n",
           after.vertices, after.ropelength, after.thickness, kkt.residual, res.stopped, res.elapsed, res.device);
    const double *x = tightrope_curve_xyz(tight);
    printf("first vertex: %.6f %.6f %.6f\n", x[0], x[1], x[2]);
    int ok = after.ropelength >= 32.7429 && after.ropelength < before.ropelength;
    tightrope_curve_free(tight);
    tightrope_curve_free(start);
    return ok ? 0 : 1;
}
