/* This file contains `tightrope devices [--json]`: the serial reference and
 * every OpenCL device, like `clinfo -l`, with double-precision status and why
 * a device cannot be used; marks the one "auto" (or TIGHTROPE_DEVICE) would
 * pick. It asks the backend registry (tr_backend_list_devices). */
#include <stdio.h>
#include <string.h>

#include "backend/backend.h"
#include "cli/cli.h"
#include "util/json.h"

static void usage(FILE *f)
{
    fprintf(f, "usage: tightrope devices [--json]\n"
               "Lists the serial reference and every OpenCL device with its P:D index,\n"
               "double-precision support and, for an unusable device, the reason.\n"
               "Select one with --device reference|auto|opencl|P:D|NAME-PART or TIGHTROPE_DEVICE;\n"
               "NAME-PART is part of a device, platform or platform-vendor name (e.g. pocl).\n");
}

int tr_cmd_devices(int argc, char **argv)
{
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--json"))
            json = 1;
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            return 0;
        } else {
            fprintf(stderr, "tightrope devices: unknown option '%s' (see tightrope devices --help)\n", argv[i]);
            return 2;
        }
    }
    tr_error err = {{0}};
    tr_device_list l;
    if (tr_backend_list_devices(&l, &err) != TR_OK) {
        fprintf(stderr, "tightrope devices: %s\n", err.msg);
        return 1;
    }

    if (json) {
        printf("{\"default_spec\": ");
        tr_json_fputs(stdout, l.default_spec);
        printf(", \"selected\": ");
        if (!l.picked)
            printf("null");
        else
            printf("\"%s\"", l.selected);
        printf(", \"opencl_absent_reason\": ");
        if (l.n == 0)
            tr_json_fputs(stdout, l.none_reason);
        else
            printf("null");
        printf(",\n \"devices\": [\n  {\"id\": \"reference\", \"name\": \"serial reference (host C)\", "
               "\"type\": \"host\", \"fp64\": true, \"usable\": true, \"reason\": null}");
        for (int i = 0; i < l.n; i++) {
            const tr_device_desc *d = &l.dev[i];
            printf(",\n  {\"id\": \"%s\", \"platform\": ", d->id);
            tr_json_fputs(stdout, d->platform);
            printf(", \"platform_vendor\": ");
            tr_json_fputs(stdout, d->platform_vendor);
            printf(", \"name\": ");
            tr_json_fputs(stdout, d->name);
            printf(", \"vendor\": ");
            tr_json_fputs(stdout, d->vendor);
            printf(", \"version\": ");
            tr_json_fputs(stdout, d->version);
            printf(", \"driver\": ");
            tr_json_fputs(stdout, d->driver);
            printf(", \"type\": \"%s\", \"compute_units\": %u, \"clock_mhz\": %u, "
                   "\"global_mem_bytes\": %llu, \"fp64\": %s, \"usable\": %s, \"reason\": ",
                   d->type, d->compute_units, d->clock_mhz, d->global_mem, d->fp64 ? "true" : "false",
                   d->usable ? "true" : "false");
            if (d->usable)
                printf("null");
            else
                tr_json_fputs(stdout, d->reason);
            printf("}");
        }
        printf("\n ]}\n");
    } else {
        int ref_sel = l.picked && !strcmp(l.selected, "reference");
        printf("%c reference  serial reference (host C)  fp64 yes\n", ref_sel ? '*' : ' ');
        for (int i = 0; i < l.n; i++) {
            const tr_device_desc *d = &l.dev[i];
            int sel = l.picked && !strcmp(l.selected, d->id);
            printf("%c %s        %s / %s  [%s, %u CU, %u MHz, %llu MiB]  fp64 %s", sel ? '*' : ' ', d->id,
                   d->platform, d->name, d->type, d->compute_units, d->clock_mhz, d->global_mem >> 20,
                   d->fp64 ? "yes" : "no");
            if (!d->usable)
                printf("  UNUSABLE: %s", d->reason);
            printf("\n");
        }
        if (l.n == 0)
            printf("  (no opencl devices: %s)\n", l.none_reason);
        if (!l.picked)
            printf("selection '%s': %s\n", l.default_spec, l.pick_error);
        else
            printf("* = selected by '%s'%s%s\n", l.default_spec, l.warning[0] ? "; " : "", l.warning);
    }
    tr_backend_device_list_free(&l);
    return 0;
}
