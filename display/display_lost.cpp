#include "display/display_lost.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <utility>

namespace rp::display {
namespace {

// Xlib takes a plain function pointer with no user data, so what it must call lives here.
std::function<void()>& saver() {
  static std::function<void()> save;
  return save;
}

// Xlib's XIOErrorHandler, without the X11 headers: int (*)(Display*).
using IoErrorHandler = int (*)(void*);

extern "C" int on_io_error(void*) {
  static bool running = false;  // a failing X call inside `save` must not run it again
  if (!saver()) std::fputs("rolypoly: error: lost the connection to the display\n", stderr);
  if (!running && saver()) {
    running = true;
    try {
      saver()();
    } catch (...) {
    }
  }
  std::fflush(nullptr);
  std::exit(1);  // what Xlib does after its handler; exit, not _exit: stdio is flushed
}

}  // namespace

void on_display_lost(std::function<void()> save) {
  saver() = std::move(save);
  static bool installed = false;
  if (installed) return;
  // RTLD_NOLOAD: only the libX11 already in the process (GLFW's); none means no X11 window.
  void* x11 = dlopen("libX11.so.6", RTLD_LAZY | RTLD_NOLOAD);
  if (!x11) return;
  using SetHandler = IoErrorHandler (*)(IoErrorHandler);
  if (auto set = reinterpret_cast<SetHandler>(dlsym(x11, "XSetIOErrorHandler"))) {
    set(on_io_error);
    installed = true;
  }
  dlclose(x11);  // GLFW keeps it loaded; the handler stays registered in it
}

}  // namespace rp::display
