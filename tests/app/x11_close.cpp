#include "x11_close.h"

#include <dlfcn.h>

#include <X11/Xlib.h>

namespace rp::test {

std::string send_wm_delete_window(const std::string& display, unsigned long window) {
  void* lib = dlopen("libX11.so.6", RTLD_NOW | RTLD_LOCAL);
  if (lib == nullptr) return std::string("cannot load libX11.so.6: ") + dlerror();
  using OpenDisplay = ::Display* (*)(const char*);
  using InternAtom = Atom (*)(::Display*, const char*, int);
  using SendEvent = Status (*)(::Display*, ::Window, int, long, XEvent*);
  using Sync = int (*)(::Display*, int);
  using CloseDisplay = int (*)(::Display*);
  auto open_display = reinterpret_cast<OpenDisplay>(dlsym(lib, "XOpenDisplay"));
  auto intern_atom = reinterpret_cast<InternAtom>(dlsym(lib, "XInternAtom"));
  auto send_event = reinterpret_cast<SendEvent>(dlsym(lib, "XSendEvent"));
  auto sync = reinterpret_cast<Sync>(dlsym(lib, "XSync"));
  auto close_display = reinterpret_cast<CloseDisplay>(dlsym(lib, "XCloseDisplay"));
  std::string error;
  if (!open_display || !intern_atom || !send_event || !sync || !close_display) {
    error = "libX11.so.6 lacks XOpenDisplay/XInternAtom/XSendEvent/XSync/XCloseDisplay";
  } else if (::Display* d = open_display(display.c_str()); d == nullptr) {
    error = "cannot open X display " + display;
  } else {
    XEvent event{};
    event.xclient.type = ClientMessage;
    event.xclient.window = window;
    event.xclient.message_type = intern_atom(d, "WM_PROTOCOLS", False);
    event.xclient.format = 32;
    event.xclient.data.l[0] = static_cast<long>(intern_atom(d, "WM_DELETE_WINDOW", False));
    event.xclient.data.l[1] = CurrentTime;
    if (send_event(d, window, False, NoEventMask, &event) == 0)
      error = "XSendEvent failed";
    sync(d, False);  // delivered before the connection closes
    close_display(d);
  }
  dlclose(lib);
  return error;
}

}  // namespace rp::test
