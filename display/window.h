// A GLFW window that shows finished RGBA8 images. It knows nothing of OpenCL or the scene: the
// image is uploaded into one texture and drawn as one quad (legacy OpenGL, no shaders), scaled
// to fit the window with black bars (letterbox) and exactly 1:1 with nearest sampling when the
// framebuffer has the image's size.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

struct GLFWwindow;

namespace rp::display {

// The window cannot be opened: no display, no OpenGL, GLFW failed. The message says why.
class DisplayError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Why no window can be opened in this environment ("" when a display looks available). Checks
// the DISPLAY / WAYLAND_DISPLAY variables only; opening may still fail later.
std::string missing_display_reason();

// Input the window collected since the last take_events(). Keys are the printable ones the app
// uses ('A'-'Z', '0'-'9', ' '), reported on press, and Home (its own type). Mouse events are the
// left button; cursor positions are in image pixels (continuous, (0,0) the top-left corner of
// the image, y down), so letterboxing and HiDPI scaling are already undone. Moves are reported
// only while the left button is held (that is all a drag needs). Look: with set_look_drag(true),
// the cursor's movement while the right button is held, in screen pixels (x, y: right, down;
// not image pixels, so turning does not depend on how the image is scaled). Scroll: y holds
// the wheel's notches, positive away from the user.
struct WindowEvent {
  enum class Type { Key, MouseDown, MouseUp, MouseMove, Look, Scroll, Home };
  Type type = Type::Key;
  char key = 0;
  float x = 0.0f, y = 0.0f;
};

class Window {
 public:
  // Opens a visible, resizable window whose framebuffer is width x height pixels on a normal
  // (non-HiDPI) screen. Throws DisplayError when there is no display or GLFW/OpenGL fail.
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  // Uploads `rgba` (width * height * 4 bytes, top row first) and shows it: draw, swap buffers.
  void present(const uint8_t* rgba, int width, int height);

  // Processes pending window events (keys, mouse, resize, close). Esc requests closing.
  void poll_events();
  // Events gathered by poll_events() since the last call, in order.
  std::vector<WindowEvent> take_events();
  bool should_close() const;
  // Whether the key ('A'-'Z') is down now (polled: held keys, not presses).
  bool key_held(char key) const;
  // Right-button drags report Look events; the cursor is hidden and unbounded while the button
  // is held (a fly camera's mouse look). Off by default: the right button is ignored.
  void set_look_drag(bool enabled);
  void set_title(const std::string& title);

  // Current framebuffer size in pixels.
  void framebuffer_size(int& width, int& height) const;

  // What the window shows: re-draws the last presented image into the back buffer and reads it
  // with glReadPixels. `out` = width * height * 4 bytes RGBA8, top row first, at the framebuffer
  // size (returned in width/height). Throws DisplayError if nothing was presented yet.
  void read_back(std::vector<uint8_t>& out, int& width, int& height);

 private:
  void draw();
  // Where the image is drawn in the framebuffer (letterboxed): origin from the top-left, size.
  void image_rect(int& x, int& y, int& w, int& h) const;
  // Window (screen) coordinates -> image pixels.
  void to_image(double wx, double wy, float& ix, float& iy) const;

  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void on_mouse_button(GLFWwindow* window, int button, int action, int mods);
  static void on_cursor(GLFWwindow* window, double x, double y);
  static void on_scroll(GLFWwindow* window, double x, double y);

  GLFWwindow* window_ = nullptr;
  unsigned int texture_ = 0;  // GL texture name holding the last presented image
  int image_width_ = 0, image_height_ = 0;
  bool left_down_ = false;
  bool look_drag_ = false;
  bool looking_ = false;            // the right button is held with look_drag_ on
  double look_x_ = 0.0, look_y_ = 0.0;  // the cursor when the last Look event was made
  std::vector<WindowEvent> events_;
};

}  // namespace rp::display
