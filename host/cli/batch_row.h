/* One knot's line of the batch table, and the record file that holds it in
 * the output folder (NAME.row.tsv: the table's header and this one line).
 * The record is written last, after the tight curve, so its presence is
 * what "this knot is done" means; the table is rebuilt from the records,
 * whichever process (a GNU parallel job, a SLURM array task) wrote them.
 *
 * A record names the start it came from (tr_batch_knot_start_id: a hash of
 * the start file's bytes, or of the name and notation of a start by name):
 * a knot's name alone does not say which curve it was, and a manifest
 * pointed at another file, or a start edited, must not leave the old
 * result in the table or let --merge take it for this one. It also says
 * where the start came from (a file, or the table's name: "knot:3_1") and
 * whether the tightened curve was found to be the start's knot type. */
#ifndef TR_BATCH_ROW_H
#define TR_BATCH_ROW_H

#include <stddef.h>

#include "cli/batch_manifest.h"
#include "util/error.h"
#include "util/text_file.h"

/* A start's identity: 16 hex digits and the NUL; "" unknown. */
#define TR_BATCH_ID_SIZE 17

typedef struct tr_batch_row {
    char knot[TR_BATCH_NAME_MAX + 1];
    size_t n;
    double ropelength, thickness, minrad, dcsd;
    double kkt_residual; /* NAN: not certified (written '-') */
    double time_s;       /* the run's seconds, runs before a resume included */
    int tries;
    long steps;
    char stop[32]; /* why the run stopped (tr_stop_reason_name) */
    int resumed;   /* 1: its last run continued from a checkpoint */
    long seed;     /* the roads' --seed; -1 unknown (a resumed run, a record of before) */
    int road;      /* the road written, 1-based; 0 unknown */
    char start[TR_BATCH_ID_SIZE]; /* the start's identity; "" unknown (a record of before) */
    /* "file", or a start by name's source ("knot:3_1", tr_batch_knot);
     * "" unknown (a record of before) */
    char source[48];
    /* the type check of the run (tighten's: the curve written has its
     * start's invariants): 1 kept, 0 not checked (no invariant the exact
     * arithmetic takes), -1 unknown (a record of before) */
    int type_checked;
} tr_batch_row;

/* The table's column names, tab-separated, no newline. */
const char *tr_batch_row_header(void);

/* Appends r as one tab-separated line (no newline). */
void tr_batch_row_format(tr_text *t, const tr_batch_row *r);

/* Appends r's members as JSON ("knot": ..., "resumed": ...), without the
 * braces, so that the table can add its comparison to the object. */
void tr_batch_row_json_fields(tr_text *t, const tr_batch_row *r);

/* Writes r to path atomically (the header line and its line). */
int tr_batch_row_write(const char *path, const tr_batch_row *r, tr_error *err);

/* Reads a record; TR_EPARSE "PATH:LINE: ..." for anything else. A record
 * written before the seed and road columns, before the start column, or
 * before the source and type_check columns, is read with them unknown. */
int tr_batch_row_read(const char *path, tr_batch_row *r, tr_error *err);

/* The identity of a start file: the 64-bit FNV-1a hash of its bytes, as
 * 16 hex digits, so that a start renamed or moved is the same start and
 * one edited in place is another. Anything but a regular file (a FIFO
 * would be drained, a device never ends) has none: id "". TR_EIO when the
 * file cannot be read. */
int tr_batch_start_id(const char *path, char id[TR_BATCH_ID_SIZE], tr_error *err);

/* The identity of knot k's start: its file's (tr_batch_start_id), or for
 * a start by name the same hash of its source and notation (the name and
 * the braid word the start is made from), so that a start by name is the
 * same start on every machine and in every batch, before it is made and
 * whatever its made file's last digits; the made file itself (OUT/starts)
 * is the batch's and plays no part. */
int tr_batch_knot_start_id(const tr_batch_knot *k, char id[TR_BATCH_ID_SIZE], tr_error *err);

/* The start a checkpoint continues, in a file beside it (NAME.start): the
 * checkpoint holds the resampled, scaled curve, not the start's bytes, so
 * without it a resumed run could not tell which start it came from. Write
 * writes id atomically; read gets it, or returns 1 (id "") when there is
 * no such file, TR_EPARSE for anything but an identity. */
int tr_batch_start_write(const char *path, const char *id, tr_error *err);
int tr_batch_start_read(const char *path, char id[TR_BATCH_ID_SIZE], tr_error *err);

#endif
