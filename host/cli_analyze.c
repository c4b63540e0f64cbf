/* PLACEHOLDER: replaced by the real 'analyze' command. */
#include <stdio.h>

#include "cli.h"

int tr_cmd_analyze(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "tightrope analyze: not built yet\n");
    return 2;
}
