#include "display/window.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <GLFW/glfw3.h>  // includes <GL/gl.h>: legacy OpenGL 1.1 entry points, no loader needed

namespace rp::display {
namespace {

bool env_set(const char* name) {
  const char* v = std::getenv(name);
  return v && *v;
}

// GLFW's description of its most recent error, or a fallback.
std::string glfw_error(const char* fallback) {
  const char* description = nullptr;
  if (glfwGetError(&description) != GLFW_NO_ERROR && description) return description;
  return fallback;
}

}  // namespace

std::string missing_display_reason() {
  if (!env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY"))
    return "no display: neither DISPLAY nor WAYLAND_DISPLAY is set";
  return "";
}

Window::Window(int width, int height, const std::string& title) {
  if (std::string why = missing_display_reason(); !why.empty()) throw DisplayError(why);
  if (glfwInit() != GLFW_TRUE)
    throw DisplayError("cannot initialise GLFW: " + glfw_error("unknown error"));
  // Default hints give a compatibility context (OpenGL 2.x+), which has the fixed-function
  // textured quad used below. No scaling to the monitor: one framebuffer pixel per image pixel.
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);
  glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    std::string why = glfw_error("unknown error");
    glfwTerminate();
    throw DisplayError("cannot open a window with OpenGL: " + why);
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, on_key);
  glfwSetMouseButtonCallback(window_, on_mouse_button);
  glfwSetCursorPosCallback(window_, on_cursor);
  glfwSetScrollCallback(window_, on_scroll);

  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glDisable(GL_DITHER);  // keep presented pixels bit-exact
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
}

Window::~Window() {
  if (window_) {
    glfwMakeContextCurrent(window_);
    if (texture_) glDeleteTextures(1, &texture_);
    glfwDestroyWindow(window_);
  }
  glfwTerminate();
}

void Window::present(const uint8_t* rgba, int width, int height) {
  glfwMakeContextCurrent(window_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  // Texture row 0 = image row 0 (the top row); draw() maps t = 0 to the top of the quad.
  if (width != image_width_ || height != image_height_) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    image_width_ = width;
    image_height_ = height;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  }
  draw();
  glfwSwapBuffers(window_);
}

void Window::draw() {
  int fb_w = 0, fb_h = 0;
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  glViewport(0, 0, fb_w, fb_h);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (image_width_ <= 0 || image_height_ <= 0 || fb_w <= 0 || fb_h <= 0) return;

  int left = 0, top = 0, draw_w = 0, draw_h = 0;
  image_rect(left, top, draw_w, draw_h);
  glViewport(left, fb_h - top - draw_h, draw_w, draw_h);  // GL's origin is the bottom-left

  // At 1:1 every pixel centre lands on a texel centre: nearest sampling reproduces the image
  // exactly. Scaled, linear filtering looks better.
  bool one_to_one = draw_w == image_width_ && draw_h == image_height_;
  GLint filter = one_to_one ? GL_NEAREST : GL_LINEAR;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);

  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glEnable(GL_TEXTURE_2D);
  // The quad fills the viewport in NDC; GL's y points up, image rows go down: t = 0 at the top.
  glBegin(GL_QUADS);
  glTexCoord2f(0.0f, 1.0f);
  glVertex2f(-1.0f, -1.0f);
  glTexCoord2f(1.0f, 1.0f);
  glVertex2f(1.0f, -1.0f);
  glTexCoord2f(1.0f, 0.0f);
  glVertex2f(1.0f, 1.0f);
  glTexCoord2f(0.0f, 0.0f);
  glVertex2f(-1.0f, 1.0f);
  glEnd();
  glDisable(GL_TEXTURE_2D);
}

void Window::image_rect(int& x, int& y, int& w, int& h) const {
  int fb_w = 0, fb_h = 0;
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  if (image_width_ <= 0 || image_height_ <= 0 || fb_w <= 0 || fb_h <= 0) {
    x = y = 0;
    w = std::max(fb_w, 1);
    h = std::max(fb_h, 1);
    return;
  }
  // Largest centred rectangle with the image's aspect ratio (letterbox / pillarbox).
  double scale = std::min(double(fb_w) / image_width_, double(fb_h) / image_height_);
  w = std::max(1, int(std::lround(image_width_ * scale)));
  h = std::max(1, int(std::lround(image_height_ * scale)));
  x = (fb_w - w) / 2;
  y = (fb_h - h) - (fb_h - h) / 2;  // same split as the GL viewport, measured from the top
}

void Window::to_image(double wx, double wy, float& ix, float& iy) const {
  int win_w = 0, win_h = 0, fb_w = 0, fb_h = 0;
  glfwGetWindowSize(window_, &win_w, &win_h);
  glfwGetFramebufferSize(window_, &fb_w, &fb_h);
  double sx = win_w > 0 ? double(fb_w) / win_w : 1.0;  // HiDPI: framebuffer pixels per point
  double sy = win_h > 0 ? double(fb_h) / win_h : 1.0;
  int x = 0, y = 0, w = 1, h = 1;
  image_rect(x, y, w, h);
  double iw = image_width_ > 0 ? image_width_ : w, ih = image_height_ > 0 ? image_height_ : h;
  ix = float((wx * sx - x) * iw / w);
  iy = float((wy * sy - y) * ih / h);
}

void Window::on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action != GLFW_PRESS) return;
  if (key == GLFW_KEY_ESCAPE) {
    glfwSetWindowShouldClose(window, GLFW_TRUE);
    return;
  }
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (!self) return;
  if (key == GLFW_KEY_HOME) {
    self->events_.push_back({WindowEvent::Type::Home, 0, 0.0f, 0.0f});
    return;
  }
  // GLFW key codes for letters, digits and space are their ASCII codes.
  bool printable = key == GLFW_KEY_SPACE || (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) ||
                   (key >= GLFW_KEY_0 && key <= GLFW_KEY_9);
  if (printable) self->events_.push_back({WindowEvent::Type::Key, char(key), 0.0f, 0.0f});
}

void Window::on_mouse_button(GLFWwindow* window, int button, int action, int /*mods*/) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (!self) return;
  if (button == GLFW_MOUSE_BUTTON_RIGHT) {
    if (action == GLFW_PRESS && self->look_drag_) {
      // A disabled cursor is hidden and not stopped by the screen's edges: a drag can turn
      // any amount. Its (virtual) position keeps counting from where it was.
      glfwSetInputMode(window, GLFW_CURSOR, GLFW_CURSOR_DISABLED);
      glfwGetCursorPos(window, &self->look_x_, &self->look_y_);
      self->looking_ = true;
    } else if (action == GLFW_RELEASE && self->looking_) {
      glfwSetInputMode(window, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
      self->looking_ = false;
    }
    return;
  }
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  double cx = 0.0, cy = 0.0;
  glfwGetCursorPos(window, &cx, &cy);
  WindowEvent e;
  e.type = action == GLFW_PRESS ? WindowEvent::Type::MouseDown : WindowEvent::Type::MouseUp;
  self->to_image(cx, cy, e.x, e.y);
  self->left_down_ = action == GLFW_PRESS;
  self->events_.push_back(e);
}

void Window::on_cursor(GLFWwindow* window, double x, double y) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (!self) return;
  if (self->looking_) {
    self->events_.push_back({WindowEvent::Type::Look, 0, float(x - self->look_x_),
                             float(y - self->look_y_)});
    self->look_x_ = x;
    self->look_y_ = y;
  }
  if (!self->left_down_) return;
  WindowEvent e;
  e.type = WindowEvent::Type::MouseMove;
  self->to_image(x, y, e.x, e.y);
  self->events_.push_back(e);
}

void Window::on_scroll(GLFWwindow* window, double /*x*/, double y) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (self && y != 0.0) self->events_.push_back({WindowEvent::Type::Scroll, 0, 0.0f, float(y)});
}

bool Window::key_held(char key) const {
  if (key < 'A' || key > 'Z') return false;
  return glfwGetKey(window_, int(key)) == GLFW_PRESS;  // GLFW_KEY_A..Z are 'A'..'Z'
}

void Window::set_look_drag(bool enabled) {
  look_drag_ = enabled;
  if (!enabled && looking_) {
    glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_NORMAL);
    looking_ = false;
  }
}

void Window::poll_events() { glfwPollEvents(); }

std::vector<WindowEvent> Window::take_events() {
  std::vector<WindowEvent> out;
  out.swap(events_);
  return out;
}

bool Window::should_close() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }

void Window::set_title(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

void Window::framebuffer_size(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}

void Window::read_back(std::vector<uint8_t>& out, int& width, int& height) {
  if (image_width_ <= 0) throw DisplayError("read_back: nothing has been presented yet");
  glfwMakeContextCurrent(window_);
  draw();
  glFinish();
  glfwGetFramebufferSize(window_, &width, &height);
  size_t row = size_t(width) * 4;
  std::vector<uint8_t> bottom_up(row * size_t(height));
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  if (GLenum err = glGetError(); err != GL_NO_ERROR)
    throw DisplayError("glReadPixels failed (GL error " + std::to_string(err) + ")");
  // glReadPixels returns the bottom row first; images here are top row first.
  out.resize(bottom_up.size());
  for (int y = 0; y < height; ++y)
    std::memcpy(out.data() + size_t(y) * row, bottom_up.data() + size_t(height - 1 - y) * row,
                row);
}

}  // namespace rp::display
