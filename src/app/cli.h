// Command line of `rolypoly` (CLI11): parses, dispatches to the subcommands, and turns every
// error into one message on stderr.
//
// Exit codes: 0 success; 1 runtime error ("rolypoly: error: <message>": no OpenCL platform,
// unknown device, kernel build failure with its build log, missing/corrupt texture, no display,
// unwritable output, a size the device's memory cannot hold); 2 usage error (unknown option or
// subcommand, bad value: "rolypoly: error: <CLI11's message>"); 130 `render` interrupted by
// SIGINT / SIGTERM (checked between frames; every written frame is complete).
#pragma once

namespace rp::app {

int run_cli(int argc, char** argv);

}  // namespace rp::app
