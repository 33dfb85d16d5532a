// rolypoly: see README.md for the subcommands, src/cli/cli.h for exit codes.
#include "cli/cli.h"

int main(int argc, char** argv) { return rp::cli::run_cli(argc, argv); }
