#define GLFW_INCLUDE_VULKAN
#include "dyngi/engine/platform/window.h"

#include <GLFW/glfw3.h>

#include "dyngi/engine/render/vk_common.h"

namespace dyngi::platform {
namespace {
int gGlfwUsers = 0;
std::string gLastGlfwError;
void onGlfwError(int, const char* description) { gLastGlfwError = description ? description : "unknown GLFW error"; }
}  // namespace

std::unique_ptr<Window> Window::create(uint32_t width, uint32_t height, const std::string& title, std::string* whyNot) {
  glfwSetErrorCallback(onGlfwError);
  if (gGlfwUsers == 0 && !glfwInit()) {
    if (whyNot) *whyNot = "glfwInit failed (" + (gLastGlfwError.empty() ? std::string("no display?") : gLastGlfwError) + ")";
    return nullptr;
  }
  ++gGlfwUsers;
  std::unique_ptr<Window> w(new Window());
  if (!glfwVulkanSupported()) {
    if (whyNot) *whyNot = "GLFW reports no Vulkan support for windows";
    return nullptr;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  w->window_ = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
  if (!w->window_) {
    if (whyNot) *whyNot = "glfwCreateWindow failed (" + gLastGlfwError + ")";
    return nullptr;
  }
  glfwSetWindowUserPointer(w->window_, w.get());
  glfwSetScrollCallback(w->window_, [](GLFWwindow* gw, double, double y) {
    static_cast<Window*>(glfwGetWindowUserPointer(gw))->scrollPending_ += y;
  });
  return w;
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
  if (--gGlfwUsers == 0) glfwTerminate();
}

std::vector<const char*> Window::requiredInstanceExtensions() {
  uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  return std::vector<const char*>(names, names + n);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  DYNGI_VK(glfwCreateWindowSurface(instance, window_, nullptr, &surface));
  return surface;
}

bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
void Window::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void Window::pollEvents() {
  glfwPollEvents();
  double x, y;
  glfwGetCursorPos(window_, &x, &y);
  dx_ = haveCursor_ ? x - lastX_ : 0.0;
  dy_ = haveCursor_ ? y - lastY_ : 0.0;
  lastX_ = x;
  lastY_ = y;
  haveCursor_ = true;
  scroll_ = scrollPending_;
  scrollPending_ = 0;
}

void Window::cursorPosition(double& x, double& y) const {
  // GLFW reports the cursor in window coordinates; the framebuffer may have more pixels (HiDPI).
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  x = ww > 0 ? lastX_ * fw / ww : lastX_;
  y = wh > 0 ? lastY_ * fh / wh : lastY_;
}
void Window::waitEvents() { glfwWaitEventsTimeout(0.1); }

void Window::framebufferSize(uint32_t& width, uint32_t& height) const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  width = uint32_t(w > 0 ? w : 0);
  height = uint32_t(h > 0 ? h : 0);
}
bool Window::keyDown(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }
bool Window::mouseButtonDown(int button) const { return glfwGetMouseButton(window_, button) == GLFW_PRESS; }
void Window::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }
void Window::requestSize(uint32_t width, uint32_t height) { glfwSetWindowSize(window_, int(width), int(height)); }

}  // namespace dyngi::platform
