// rolypoly: see README.md for the subcommands, src/app/cli.h for exit codes.
#include "app/cli.h"

int main(int argc, char** argv) { return rp::app::run_cli(argc, argv); }
