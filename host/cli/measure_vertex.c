/* `tightrope measure --contacts vertex` (measure_vertex.h). */
#include "cli/measure_vertex.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "oracle/vertex_thickness.h"
#include "util/json.h"

static void json_num(tr_text *t, const char *key, double v)
{
    tr_text_printf(t, "\"%s\": ", key);
    tr_json_number(t, "%.17g", v);
    tr_text_printf(t, ", ");
}

int tr_measure_vertex_append(tr_text *t, const tr_curve *c, const tr_thickness *rawdon, int json, tr_error *err)
{
    tr_vertex_thickness v;
    int rc = tr_vertex_thickness_measure(c, NULL, rawdon, &v, err);
    if (rc)
        return rc;
    int paired = v.vertex_dmin < INFINITY;
    if (json) {
        /* K is null when no pair on one component counts (an infinite R). */
        tr_text_printf(t, ", \"contacts\": \"vertex\", \"vertex_contacts\": {");
        json_num(t, "edge", v.edge);
        if (v.exclusion == SIZE_MAX)
            tr_text_printf(t, "\"exclusion\": null, ");
        else
            tr_text_printf(t, "\"exclusion\": %zu, ", v.exclusion);
        json_num(t, "radius", v.radius);
        json_num(t, "minrad", v.minrad);
        json_num(t, "vertex_dmin", v.vertex_dmin);
        if (paired)
            tr_text_printf(t, "\"vertex_pair\": [%zu, %zu], ", v.vj, v.vi);
        json_num(t, "thickness", v.thickness);
        tr_text_printf(t, "\"ropelength\": ");
        tr_json_number(t, "%.17g", v.ropelength);
        tr_text_printf(t, "}");
        return TR_OK;
    }
    tr_text_printf(t, "contacts vertex (SP-FEM's model; the table above is Rawdon's): vertices count as a pair "
                      "on different components or >= K = ceil(pi R / e) apart along one, R the thickness\n");
    tr_text_printf(t, "%-10s %22s %9s %22s %22s %22s %22s\n", "", "e", "K", "minrad", "vertex_dmin", "thickness",
                   "ropelength");
    char k[24];
    if (v.exclusion == SIZE_MAX)
        snprintf(k, sizeof k, "inf");
    else
        snprintf(k, sizeof k, "%zu", v.exclusion);
    tr_text_printf(t, "%-10s %22.15g %9s %22.15g %22.15g %22.15g %22.15g\n", "vertex", v.edge, k, v.minrad,
                   v.vertex_dmin, v.thickness, v.ropelength);
    if (paired)
        tr_text_printf(t, "closest vertices %zu and %zu (global indices)\n", v.vj, v.vi);
    return TR_OK;
}
