/* Subcommands of the tightrope program. Each returns the process exit status:
 * 0 success; 2 bad input, bad usage, or an output file that cannot be
 * written (the user can fix all three); 1 anything else: a run that did not
 * reach its goal, a device failure, out of memory. The command layer is the
 * only place that prints errors. */
#ifndef TR_CLI_H
#define TR_CLI_H

int tr_cmd_measure(int argc, char **argv);
int tr_cmd_make(int argc, char **argv);
int tr_cmd_tighten(int argc, char **argv);
int tr_cmd_devices(int argc, char **argv);
int tr_cmd_bench(int argc, char **argv);
int tr_cmd_analyze(int argc, char **argv);

#endif
