// Asks an X11 window to close the way a window manager does when its close button is clicked:
// a WM_PROTOCOLS client message carrying WM_DELETE_WINDOW (ICCCM 4.2.8.1). The application
// decides what to do (GLFW sets glfwWindowShouldClose). libX11 is loaded at run time (dlopen),
// so test_app needs no X11 link dependency.
#pragma once

#include <string>

namespace rp::test {

// Sends the message to `window` (an X window id, e.g. from `xdotool search`) on `display`
// (e.g. ":99"). Returns "" on success, else what went wrong.
std::string send_wm_delete_window(const std::string& display, unsigned long window);

}  // namespace rp::test
