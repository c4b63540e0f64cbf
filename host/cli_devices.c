/* PLACEHOLDER: replaced by the real 'devices' command. */
#include <stdio.h>

#include "cli.h"

int tr_cmd_devices(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "tightrope devices: not built yet\n");
    return 2;
}
