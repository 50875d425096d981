#pragma once
// A GLFW window with the input state the sample's fly camera needs. Creation fails cleanly (returns
// nullptr with a reason) when there is no display, so callers can fall back to headless.
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace dyngi::platform {

class Window {
 public:
  static std::unique_ptr<Window> create(uint32_t width, uint32_t height, const std::string& title, std::string* whyNot);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  static std::vector<const char*> requiredInstanceExtensions();
  VkSurfaceKHR createSurface(VkInstance instance) const;

  bool shouldClose() const;
  void requestClose();
  void pollEvents();
  void waitEvents();  // blocks until something happens (minimised windows)
  void framebufferSize(uint32_t& width, uint32_t& height) const;
  bool keyDown(int glfwKey) const;
  bool mouseButtonDown(int button) const;
  // Cursor movement since the previous pollEvents().
  void mouseDelta(double& dx, double& dy) const { dx = dx_; dy = dy_; }
  // The cursor in framebuffer pixels (top left 0,0) at the last pollEvents().
  void cursorPosition(double& x, double& y) const;
  // Scroll since the previous pollEvents() (wheel notches; y up).
  double scrollDelta() const { return scroll_; }
  void setTitle(const std::string& title);
  // Asks for a new client size (the framebuffer follows at the next pollEvents; a window manager may refuse).
  void requestSize(uint32_t width, uint32_t height);

 private:
  Window() = default;
  GLFWwindow* window_ = nullptr;
  double lastX_ = 0, lastY_ = 0, dx_ = 0, dy_ = 0;
  double scroll_ = 0, scrollPending_ = 0;
  bool haveCursor_ = false;
};

}  // namespace dyngi::platform
