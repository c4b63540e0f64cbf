/* This file contains the tube pictures' gnuplot data and script (tube_script.h). */
#include "analysis/tube_script.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/tube_mesh.h"
#include "util/text_file.h"
#include "util/vec3.h"

const char *const tr_tube_png_names[TR_TUBE_PNGS] = {"tube_front.png", "tube_top.png", "tube_side.png",
                                                     "tube_struts.png"};

/* The struts' picture: the rope as a thin core (this radius, in rope radii)
 * and each strut drawn as a thin rod, inside the tube drawn translucent. */
#define CORE_RADIUS 0.12
#define CORE_SIDES 8
#define STRUT_RADIUS 0.025
#define STRUT_SIDES 6

/* The colour value of a vertex: the palette (tr_tube_script_text) is a
 * blue ramp over [0, 1) for the curvature of plain rope, then flat colours
 * for the two marks, so a mark never reads as a curvature. */
static double colour(const tr_tube_picture *tp, size_t r, size_t j)
{
    unsigned char m = tp->mark[r * tp->sides + j];
    if (m == TR_TUBE_CONTACT)
        return 2.5;
    if (m == TR_TUBE_MINRAD)
        return 1.5;
    double k = tp->kappa[r];
    return !(k > 0) ? 0.0 : k >= 0.999 ? 0.999 : k;
}

int tr_tube_data_text(const tr_tube_picture *tp, char **out)
{
    tr_text b = {0};
    tr_text_printf(&b, "# tube of radius 1: %zu rings of %zu vertices (each block one ring, the first again "
                       "at the end)\n# x y z colour (kappa < 1 rope, 1.5 kappa = 1 stretch, 2.5 contact)\n",
                   tp->rings, tp->sides);
    for (size_t rr = 0; rr <= tp->rings; rr++) {
        size_t r = rr % tp->rings;
        for (size_t jj = 0; jj <= tp->sides; jj++) {
            size_t j = jj % tp->sides;
            const double *q = tp->p + 3 * (r * tp->sides + j);
            tr_text_printf(&b, "%.6f %.6f %.6f %.4f\n", q[0], q[1], q[2], colour(tp, r, j));
        }
        tr_text_printf(&b, "\n");
    }
    *out = tr_text_take(&b, NULL);
    return *out ? TR_OK : TR_ENOMEM;
}

int tr_tube_struts_text(const tr_tube_picture *tp, char **out)
{
    *out = NULL;
    tr_tube_mesh core = {0};
    if (tr_tube_mesh_add(&core, tp->core, tp->rings, 1, CORE_RADIUS, CORE_SIDES, NULL) != TR_OK)
        return TR_EGEOMETRY; /* the core made the picture's tube: only memory can fail */
    tr_text b = {0};
    tr_text_printf(&b, "# the core (radius %g, %d sides, one block per ring), then %zu struts (radius %g, "
                       "%d sides, two blocks each),\n# surfaces separated by two blank lines; x y z colour "
                       "(kappa < 1 rope, 1.5 kappa = 1 stretch, 3.5 strut)\n",
                   CORE_RADIUS, CORE_SIDES, tp->nstruts, STRUT_RADIUS, STRUT_SIDES);
    for (size_t rr = 0; rr <= tp->rings; rr++) {
        size_t r = rr % tp->rings;
        int minrad = 0;
        for (size_t j = 0; j < tp->sides; j++)
            minrad |= tp->mark[r * tp->sides + j] == TR_TUBE_MINRAD;
        double k = tp->kappa[r], c = minrad ? 1.5 : !(k > 0) ? 0.0 : k >= 0.999 ? 0.999 : k;
        for (size_t jj = 0; jj <= CORE_SIDES; jj++) {
            const double *q = core.v + 3 * (r * CORE_SIDES + jj % CORE_SIDES);
            tr_text_printf(&b, "%.6f %.6f %.6f %.4f\n", q[0], q[1], q[2], c);
        }
        tr_text_printf(&b, "\n");
    }
    tr_tube_mesh_free(&core);
    for (size_t i = 0; i < tp->nstruts; i++) {
        const double *a = tp->strut + 6 * i, *e = a + 3;
        double d[3], u[3] = {0, 0, 0}, w[3];
        v3_sub(d, e, a);
        double l = v3_norm(d);
        if (!(l > 0))
            continue;
        v3_scale(d, 1.0 / l, d);
        u[fabs(d[0]) < 0.6 ? 0 : fabs(d[1]) < 0.6 ? 1 : 2] = 1.0; /* an axis well off d */
        v3_axpy(u, -v3_dot(u, d), d);
        v3_scale(u, 1.0 / v3_norm(u), u);
        v3_cross(w, d, u);
        tr_text_printf(&b, "\n");
        for (int end = 0; end < 2; end++) {
            const double *c = end ? e : a;
            for (int j = 0; j <= STRUT_SIDES; j++) {
                double phi = 2.0 * 3.14159265358979323846 * (double)(j % STRUT_SIDES) / STRUT_SIDES, q[3];
                for (int x = 0; x < 3; x++)
                    q[x] = c[x] + STRUT_RADIUS * (cos(phi) * u[x] + sin(phi) * w[x]);
                tr_text_printf(&b, "%.6f %.6f %.6f 3.5\n", q[0], q[1], q[2]);
            }
            tr_text_printf(&b, "\n");
        }
    }
    *out = tr_text_take(&b, NULL);
    return *out ? TR_OK : TR_ENOMEM;
}

/* The title goes into a gnuplot "..." string (for its line break): a
 * quote or a backslash in it would end or escape the string, so they and
 * line breaks become spaces. */
static void quote_safe(char *dst, size_t n, const char *src)
{
    size_t i = 0;
    for (; src && src[i] && i + 1 < n; i++)
        dst[i] = strchr("\"\\\n\r'", src[i]) ? ' ' : src[i];
    dst[i] = '\0';
}

int tr_tube_script_text(const tr_tube_picture *tp, const tr_tube_views *views, const char *data,
                        const char *struts, const char *const outputs[TR_TUBE_PNGS], const char *title, int px,
                        char **out)
{
    /* One scale for all three views: the farthest surface point from the
     * centre, so the pictures can be compared side by side. */
    double R = 0.0;
    for (size_t i = 0; i < tp->rings * tp->sides; i++)
        R = fmax(R, sqrt(v3_dist2(tp->p + 3 * i, views->centre)));
    R *= 1.02;
    char t[512];
    quote_safe(t, sizeof t, title);
    tr_text b = {0};
    tr_text_printf(&b,
        "# written by tightrope analyze; run in this directory: gnuplot tube.gp\n"
        "# (tightrope writes each picture to a temporary name and renames it when gnuplot is done)\n"
        "# The surface is drawn in camera coordinates: (p - c).right across, (p - c).up upwards,\n"
        "# (p - c).toward the depth, seen from +z (set view 0,0); pm3d depthorder paints the quads\n"
        "# far to near, so nearer rope hides farther rope.\n"
        "set terminal pngcairo size %d,%d noenhanced font ',%d'\n"
        "unset border; unset tics; unset colorbox\n"
        "set view 0,0,1.5\n"
        "set view equal xyz\n"
        "set margins 0,0,0,0\n"
        "R = %.6f\n"
        "set xrange [-R:R]; set yrange [-R:R]; set zrange [-R:R]\n"
        "set pm3d depthorder lighting primary 0.45 specular 0.35 spec2 0.0\n"
        "set pm3d corners2color max noborder\n"
        "set style fill solid 1.0 noborder\n"
        "# rope: pale to mid blue with the curvature; kappa = 1 stretches orange; contacts dark\n"
        "set palette defined (0 '#d8e4f2', 0.999 '#3c6cb4', 1 '#f08c28', 1.999 '#f08c28', 2 '#202040', 2.999 '#202040', \\\n"
        "                     3 '#c01828', 4 '#c01828')\n"
        "set cbrange [0:4]\n"
        "set key at screen 0.5, 0.1 center center horizontal maxrows 1 Left reverse samplen 1.5 width 2\n"
        "cx = %.9g; cy = %.9g; cz = %.9g\n"
        "px(x, y, z) = (x - cx) * rx + (y - cy) * ry + (z - cz) * rz\n"
        "py(x, y, z) = (x - cx) * ux + (y - cy) * uy + (z - cz) * uz\n"
        "pz(x, y, z) = (x - cx) * tx + (y - cy) * ty + (z - cz) * tz\n",
        px, px, px >= 600 ? 12 : px >= 400 ? 10 : 8, R, views->centre[0], views->centre[1], views->centre[2]);
    static const char *const what[TR_NVIEWS] = {"front", "top", "side"};
    for (int v = 0; v < TR_NVIEWS; v++) {
        const tr_view *w = &views->v[v];
        char along[160];
        if (v == TR_VIEW_FRONT)
            snprintf(along, sizeof along, "along %s", views->front_axis ? views->front_axis : "the view axis");
        else
            snprintf(along, sizeof along, "%s", v == TR_VIEW_TOP ? "from above the front view" : "from the right of the front view");
        tr_text_printf(&b,
            "\n# %s view: %s\n"
            "rx = %.12f; ry = %.12f; rz = %.12f\n"
            "ux = %.12f; uy = %.12f; uz = %.12f\n"
            "tx = %.12f; ty = %.12f; tz = %.12f\n"
            "set output '%s'\n"
            "set title \"%s%s%s view, %s\" offset 0,-1\n"
            "splot '%s' using (px($1,$2,$3)):(py($1,$2,$3)):(pz($1,$2,$3)):4 with pm3d notitle, \\\n"
            "  keyentry with boxes fs solid 1.0 lc rgb '#f08c28' title 'kappa = 1 (MinRad active)', \\\n"
            "  keyentry with boxes fs solid 1.0 lc rgb '#202040' title 'contact (strut)'\n",
            what[v], along, w->right[0], w->right[1], w->right[2], w->up[0], w->up[1], w->up[2],
            w->toward[0], w->toward[1], w->toward[2], outputs[v], t, *t ? "\\n" : "", what[v], along, data);
    }
    /* The struts: the front camera again, the tube translucent around the
     * core and the struts (all pm3d, so depthorder sorts them together). */
    const tr_view *w = &views->v[TR_VIEW_FRONT];
    tr_text_printf(&b,
        "\n# the struts, front view: the tube translucent, the core and %zu struts inside\n"
        "rx = %.12f; ry = %.12f; rz = %.12f\n"
        "ux = %.12f; uy = %.12f; uz = %.12f\n"
        "tx = %.12f; ty = %.12f; tz = %.12f\n"
        "set output '%s'\n"
        "set title \"%s%sstruts (%zu drawn), front view\" offset 0,-1\n"
        "splot '%s' using (px($1,$2,$3)):(py($1,$2,$3)):(pz($1,$2,$3)):4 with pm3d fs transparent solid 0.22 notitle, \\\n"
        "  '%s' using (px($1,$2,$3)):(py($1,$2,$3)):(pz($1,$2,$3)):4 with pm3d notitle, \\\n"
        "  keyentry with boxes fs solid 1.0 lc rgb '#f08c28' title 'kappa = 1 (MinRad active)', \\\n"
        "  keyentry with boxes fs solid 1.0 lc rgb '#c01828' title 'strut'\n",
        tp->nstruts, w->right[0], w->right[1], w->right[2], w->up[0], w->up[1], w->up[2], w->toward[0],
        w->toward[1], w->toward[2], outputs[TR_TUBE_PNGS - 1], t, *t ? "\\n" : "", tp->nstruts, data, struts);
    *out = tr_text_take(&b, NULL);
    return *out ? TR_OK : TR_ENOMEM;
}

int tr_tube_script_write(const char *dir, const tr_tube_picture *tp, const tr_tube_views *views,
                         const char *title, int px, tr_plot_script *ps, tr_error *err)
{
    if (px < TR_TUBE_PX_MIN || px > TR_TUBE_PX_MAX)
        return tr_fail(err, TR_EINVAL, "tube pictures of %d pixels: %d to %d", px, TR_TUBE_PX_MIN, TR_TUBE_PX_MAX);
    char dat[4096], sdat[4096], gp[4096];
    int a = snprintf(dat, sizeof dat, "%s/tube.dat", dir), g = snprintf(gp, sizeof gp, "%s/tube.gp", dir);
    int c = snprintf(sdat, sizeof sdat, "%s/struts.dat", dir);
    if (a < 0 || (size_t)a >= sizeof dat || g < 0 || (size_t)g >= sizeof gp || c < 0 || (size_t)c >= sizeof sdat)
        return tr_fail(err, TR_EINVAL, "%s: output path too long", dir);
    int rc = tr_plot_reserve(dir, tr_tube_png_names, TR_TUBE_PNGS, ps, err);
    if (rc != TR_OK)
        return rc;
    const char *outputs[TR_TUBE_PNGS];
    for (size_t v = 0; v < TR_TUBE_PNGS; v++)
        outputs[v] = tr_plot_tmp_base(ps, dir, v);
    char *text = NULL;
    if (tr_tube_data_text(tp, &text) != TR_OK)
        rc = tr_fail(err, TR_ENOMEM, "out of memory for %s", dat);
    else
        rc = tr_write_file_atomic(dat, text, strlen(text), err);
    free(text), text = NULL;
    if (rc == TR_OK && tr_tube_struts_text(tp, &text) != TR_OK)
        rc = tr_fail(err, TR_ENOMEM, "out of memory for %s", sdat);
    else if (rc == TR_OK)
        rc = tr_write_file_atomic(sdat, text, strlen(text), err);
    free(text), text = NULL;
    if (rc == TR_OK && tr_tube_script_text(tp, views, "tube.dat", "struts.dat", outputs, title, px, &text) != TR_OK)
        rc = tr_fail(err, TR_ENOMEM, "out of memory for %s", gp);
    if (rc == TR_OK)
        rc = tr_write_file_atomic(gp, text, strlen(text), err);
    free(text);
    if (rc != TR_OK)
        tr_plot_discard(ps);
    return rc;
}
