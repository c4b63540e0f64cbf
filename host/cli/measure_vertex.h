/* `tightrope measure --contacts vertex`: the vertex model's numbers
 * (oracle/vertex_thickness.h) beside Rawdon's table and JSON, kept apart
 * from cli_measure.c so that command's own output stays as it is. */
#ifndef TR_MEASURE_VERTEX_H
#define TR_MEASURE_VERTEX_H

#include "curve/curve.h"
#include "oracle/thickness.h"
#include "util/text_file.h"

/* Measures c in the vertex model (rawdon: its tr_thickness_measure result)
 * and appends to t either the JSON members `, "contacts": "vertex",
 * "vertex_contacts": {...}` (json != 0, inside the file's object) or the
 * table lines. Returns a tr_status; err says why. */
int tr_measure_vertex_append(tr_text *t, const tr_curve *c, const tr_thickness *rawdon, int json, tr_error *err);

#endif
