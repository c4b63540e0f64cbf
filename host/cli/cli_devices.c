/* tightrope devices [--json]: the serial reference and every OpenCL device,
 * like `clinfo -l`, with double-precision status and why a device cannot be
 * used; marks the one "auto" (or TIGHTROPE_DEVICE) would pick. */
#include <stdio.h>
#include <string.h>

#include "backend/opencl/cl_device.h"
#include "cli/cli.h"
#include "util/json.h"

static const char *type_name(cl_device_type t)
{
    if (t & CL_DEVICE_TYPE_GPU)
        return "gpu";
    if (t & CL_DEVICE_TYPE_ACCELERATOR)
        return "accelerator";
    if (t & CL_DEVICE_TYPE_CPU)
        return "cpu";
    return "other";
}

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
    tr_cl_device_list l;
    if (tr_cl_enumerate(&l, &err) != TR_OK) {
        fprintf(stderr, "tightrope devices: %s\n", err.msg);
        return 1;
    }
    tr_device_choice pick;
    tr_error perr = {{0}};
    int picked = tr_device_select(NULL, &pick, &perr) == TR_OK;

    if (json) {
        printf("{\"default_spec\": ");
        tr_json_fputs(stdout, tr_device_spec_default());
        printf(", \"selected\": ");
        if (!picked)
            printf("null");
        else if (pick.kind == TR_DEVICE_REFERENCE)
            printf("\"reference\"");
        else
            printf("\"%d:%d\"", pick.cl.platform, pick.cl.device);
        printf(", \"opencl_absent_reason\": ");
        if (l.n == 0)
            tr_json_fputs(stdout, l.none_reason);
        else
            printf("null");
        printf(",\n \"devices\": [\n  {\"id\": \"reference\", \"name\": \"serial reference (host C)\", "
               "\"type\": \"host\", \"fp64\": true, \"usable\": true, \"reason\": null}");
        for (int i = 0; i < l.n; i++) {
            const tr_cl_device_info *d = &l.dev[i];
            printf(",\n  {\"id\": \"%d:%d\", \"platform\": ", d->platform, d->device);
            tr_json_fputs(stdout, d->platform_name);
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
                   type_name(d->type), d->compute_units, d->clock_mhz,
                   (unsigned long long)d->global_mem, d->fp64 ? "true" : "false",
                   d->usable ? "true" : "false");
            if (d->usable)
                printf("null");
            else
                tr_json_fputs(stdout, d->reason);
            printf("}");
        }
        printf("\n ]}\n");
    } else {
        int ref_sel = picked && pick.kind == TR_DEVICE_REFERENCE;
        printf("%c reference  serial reference (host C)  fp64 yes\n", ref_sel ? '*' : ' ');
        for (int i = 0; i < l.n; i++) {
            const tr_cl_device_info *d = &l.dev[i];
            int sel = picked && pick.kind == TR_DEVICE_OPENCL && pick.cl.platform == d->platform &&
                      pick.cl.device == d->device;
            printf("%c %d:%d        %s / %s  [%s, %u CU, %u MHz, %llu MiB]  fp64 %s", sel ? '*' : ' ',
                   d->platform, d->device, d->platform_name, d->name, type_name(d->type),
                   d->compute_units, d->clock_mhz, (unsigned long long)(d->global_mem >> 20),
                   d->fp64 ? "yes" : "no");
            if (!d->usable)
                printf("  UNUSABLE: %s", d->reason);
            printf("\n");
        }
        if (l.n == 0)
            printf("  (no opencl devices: %s)\n", l.none_reason);
        if (!picked)
            printf("selection '%s': %s\n", tr_device_spec_default(), perr.msg);
        else
            printf("* = selected by '%s'%s%s\n", tr_device_spec_default(),
                   pick.warning[0] ? "; " : "", pick.warning);
    }
    tr_cl_device_list_free(&l);
    return 0;
}
