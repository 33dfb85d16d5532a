// The display connection going away (the X server shut down or crashed, an ssh -X link
// dropped): Xlib calls its I/O error handler and then ends the process with exit code 1,
// without returning to the caller, so whatever the program holds only in memory (`run
// --record`'s input log) would be lost. on_display_lost() registers what to do first.
#pragma once

#include <functional>

namespace rp::display {

// `save` runs once, on the thread whose X call failed, before the process exits with code 1
// (exceptions from it are swallowed: the process ends either way). An empty function removes
// it. X11 only: the handler goes into the libX11 that GLFW loaded (found at run time, so
// nothing links X11 directly); elsewhere (Wayland, no window yet) this does nothing.
void on_display_lost(std::function<void()> save);

}  // namespace rp::display
