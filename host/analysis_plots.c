#include "analysis_plots.h"

#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "curve_io.h"

int tr_gnuplot_available(void)
{
    const char *path = getenv("PATH");
    if (!path)
        return 0;
    char buf[4096];
    const char *p = path;
    while (*p) {
        const char *q = strchr(p, ':');
        size_t len = q ? (size_t)(q - p) : strlen(p);
        if (len && len + 9 < sizeof buf) {
            memcpy(buf, p, len);
            memcpy(buf + len, "/gnuplot", 9);
            if (access(buf, X_OK) == 0)
                return 1;
        }
        if (!q)
            break;
        p = q + 1;
    }
    return 0;
}

int tr_analysis_plots(const char *dir, const tr_analysis *a, tr_error *err)
{
    if (!tr_gnuplot_available())
        return tr_fail(err, TR_EUNSUPPORTED, "gnuplot not found on PATH (Debian package gnuplot-nox)");
    double L6 = a->L / 6.0;
    int d3 = a->sym.verdict == TR_SYM_D3;
    double xmax = d3 ? L6 : a->L;
    double z0 = 0.0, z1 = fmin(0.6, xmax);
    if (a->have_l12) {
        /* the plateau, and at least four averaged arcs either side of it */
        double w = a->l2 - a->l1, pad = fmax(0.6 * w, 4.0 * a->m * a->L / (double)a->n);
        z0 = fmax(0.0, a->l1 - pad);
        z1 = fmin(xmax, a->l2 + pad);
    }
    char *s = NULL;
    size_t cap = 16384;
    s = malloc(cap);
    if (!s)
        return tr_fail(err, TR_ENOMEM, "out of memory for the plot script");
    int n = snprintf(s, cap,
        "# written by tightrope analyze; run in this directory: gnuplot plots.gp\n"
        "set datafile separator ','\n"
        "set datafile commentschars '#'\n"
        "set terminal pngcairo size 1100,700 noenhanced font ',11'\n"
        "L = %.15g; XM = %.15g; l1 = %.15g; l2 = %.15g; have12 = %d\n"
        "set grid\n"
        "set key top right opaque\n"
        "set offsets 0, 0, graph 0.05, graph 0.05\n"
        "sec0(x, s) = (s == 0 ? x : 1/0)\n"
        "if (have12) { set arrow 1 from l1, graph 0 to l1, graph 1 nohead dt 2 lc rgb 'gray40'; "
        "set arrow 2 from l2, graph 0 to l2, graph 1 nohead dt 2 lc rgb 'gray40' }\n"
        /* 1: curvature and torsion over the representative interval */
        "set output 'curvature_torsion.png'\n"
        "set multiplot layout 2,1 title 'K_c^(%zu): curvature and torsion over [0, %s)'\n"
        "set xrange [0:XM]\n"
        "set ylabel 'curvature kappa'\n"
        "plot 'curvature.csv' every ::1 using 3:5 with points pt 7 ps 0.3 lc rgb '#a0b4d8' title 'all six sectors, folded', "
        "'' every ::1 using (sec0($2,$4)):5 with lines lw 2 lc rgb '#1f4e9c' title 'kappa (sector I)', 1 dt 3 lc rgb 'black' notitle\n"
        "set xlabel 'arclength l from the origin'\n"
        "set ylabel 'torsion tau'\n"
        "set key bottom right opaque\n"
        "plot 'torsion.csv' every ::1 using 3:6 with points pt 7 ps 0.3 lc rgb '#e0b0a0' title 'all six sectors, folded', "
        "'' every ::1 using (sec0($2,$4)):6 with lines lw 2 lc rgb '#b03020' title 'tau (sector I)'\n"
        "set key top right opaque\n"
        "unset multiplot\n"
        /* 2: the plateau region */
        "set output 'plateau_zoom.png'\n"
        "set multiplot layout 2,1 title 'plateau region (dashed: l1, l2, averaged over the symmetry images)'\n"
        "set xrange [%.15g:%.15g]\n"
        "unset xlabel\n"
        "set ylabel 'curvature kappa'\n"
        "plot 'curvature.csv' every ::1 using 3:5 with points pt 7 ps 0.4 lc rgb '#a0b4d8' title 'all six sectors, folded', "
        "'' every ::1 using (sec0($2,$4)):5 with linespoints pt 7 ps 0.4 lc rgb '#1f4e9c' title 'kappa (sector I)', 1 dt 3 lc rgb 'black' notitle\n"
        "set xlabel 'arclength l from the origin'\n"
        "set ylabel 'torsion tau'\n"
        "plot 'torsion.csv' every ::1 using 3:6 with points pt 7 ps 0.4 lc rgb '#e0b0a0' title 'all six sectors, folded', "
        "'' every ::1 using (sec0($2,$4)):6 with linespoints pt 7 ps 0.4 lc rgb '#b03020' title 'tau (sector I)'\n"
        "unset multiplot\n"
        /* 3: accumulated torsion */
        "set output 'accumulated_torsion.png'\n"
        "set title 'accumulated torsion alpha(l) from the origin'\n"
        "set xrange [0:XM]\n"
        "set xlabel 'arclength l from the origin'\n"
        "set ylabel 'alpha (rad)'\n"
        "plot 'torsion.csv' every ::1 using (sec0($2,$4)):7 with lines lw 2 lc rgb '#207020' title 'alpha'\n"
        "unset arrow\n"
        "unset title\n",
        a->L, xmax, a->have_l12 ? a->l1 : 0.0, a->have_l12 ? a->l2 : 0.0, a->have_l12, a->m,
        d3 ? "L/6" : "L", z0, z1);
    if (n < 0 || (size_t)n >= cap) {
        free(s);
        return tr_fail(err, TR_EINVAL, "plot script too long");
    }
    size_t len = (size_t)n;
    if (a->have_sigma) {
        int k = snprintf(s + len, cap - len,
            /* 4: contact-function image */
            "set output 'contact_map.png'\n"
            "set terminal pngcairo size 800,800 noenhanced font ',11'\n"
            "set title 'contact-function image: struts (l_i, l_j) and (l_j, l_i)'\n"
            "set xrange [0:L]; set yrange [0:L]; set size square\n"
            "set xlabel 'l'; set ylabel 'partner l'\n"
            "plot 'contacts.csv' every ::1 using 1:2 with points pt 7 ps 0.25 lc rgb '#303030' title 'struts', "
            "'' every ::1 using 2:1 with points pt 7 ps 0.25 lc rgb '#303030' notitle, "
            "'sigma.csv' every ::1 using 1:2 with dots lc rgb '#1f4e9c' title 'sigma-', "
            "'' every ::1 using 1:3 with dots lc rgb '#b03020' title 'sigma+'\n"
            /* 5: sigma-^9 against the diagonal */
            "set output 'sigma9.png'\n"
            "set title 'sigma-^%d(l) against the diagonal; circles: fixed points (filled: stable)'\n"
            "set xlabel 'l'; set ylabel 'sigma-^%d(l)'\n"
            "plot 'sigma.csv' every ::1 using 1:6 with dots lc rgb '#1f4e9c' title 'sigma-^%d', x lc rgb 'black' title 'diagonal', "
            "'fixed_points.csv' every ::1 using 1:($4 == 1 ? $1 : 1/0) with points pt 7 ps 1.2 lc rgb '#b03020' title 'stable', "
            "'' every ::1 using 1:($4 == 0 ? $1 : 1/0) with points pt 6 ps 1.2 lc rgb '#b03020' title 'unstable'\n",
            a->power, a->power, a->power);
        if (k < 0 || (size_t)k >= cap - len) {
            free(s);
            return tr_fail(err, TR_EINVAL, "plot script too long");
        }
        len += (size_t)k;
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/plots.gp", dir);
    int rc = tr_write_file_atomic(path, s, len, err);
    free(s);
    if (rc != TR_OK)
        return rc;
    char logp[4096];
    snprintf(logp, sizeof logp, "%s/gnuplot.log", dir);
    pid_t pid = fork();
    if (pid < 0)
        return tr_fail(err, TR_EIO, "cannot start gnuplot: fork failed");
    if (pid == 0) {
        int fd = open(logp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
            close(fd);
        }
        if (chdir(dir) != 0)
            _exit(126);
        execlp("gnuplot", "gnuplot", "plots.gp", (char *)NULL);
        _exit(127);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) < 0)
        return tr_fail(err, TR_EIO, "waiting for gnuplot failed");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return tr_fail(err, TR_EIO, "gnuplot failed (status %d); see %s", WIFEXITED(status) ? WEXITSTATUS(status) : -1, logp);
    return TR_OK;
}
