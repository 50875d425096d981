#pragma once
// The playable sample's input, one frame at a time: from the window, or replayed from an input script
// (--input-script FILE), so a scripted session runs exactly the code a person's clicks and keys run:
// the panel, picking, dragging, the hotkeys.
//
// Script lines (blank lines and # comments are skipped); FRAME is the frame the event happens in:
//   FRAME move X Y                  cursor to framebuffer pixel X, Y (top left 0, 0)
//   FRAME press left|right|middle   button down (held until released)
//   FRAME release left|right|middle
//   FRAME click X Y                 move + press now, release the next frame
//   FRAME drag X0 Y0 X1 Y1 N        press at X0, Y0, move to X1, Y1 over N frames, release after
//   FRAME key NAME                  a key pressed this frame (released the next); NAME: A-Z, 0-9, F1-F12,
//                                   DELETE, SPACE, ESCAPE, EQUAL, MINUS, TAB, ENTER
//   FRAME hold NAME | unhold NAME   a key held down from this frame / released
//   FRAME ui LABEL                  a click on the panel widget labelled LABEL (rest of the line)
//   FRAME screenshot FILE.png       after this frame renders, the displayed image (panel included)
//   FRAME resize W H                the window's size (headless: the render size) from the next frame
//   FRAME quit
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace dyngi::platform {
class Window;
}

namespace dyngi::sample {

enum MouseButton { kLeft = 0, kRight = 1, kMiddle = 2 };

struct InputFrame {
  glm::dvec2 mouse{-1.0};       // framebuffer pixels; negative: no cursor
  glm::dvec2 mouseDelta{0.0};
  bool down[3]{};               // held
  bool pressed[3]{};            // went down this frame
  bool released[3]{};           // went up this frame
  double scroll = 0;
  std::set<int> keysDown;       // GLFW key codes held
  std::set<int> keysPressed;    // went down this frame
  bool keyDown(int key) const { return keysDown.count(key) != 0; }
  bool keyPressed(int key) const { return keysPressed.count(key) != 0; }
};

// What a script asks for beside input.
struct ScriptCommand {
  enum Kind { Screenshot, Resize, Quit } kind;
  std::string path;
  glm::uvec2 size{0};  // Resize
};

class InputScript {
 public:
  // Parses the file; nullopt with `error` ("FILE:LINE: why") for a file that cannot be read or a bad line.
  static constexpr uint64_t kMaxScriptBytes = 16u << 20;  // a script is text: a larger file is not one
  static std::optional<InputScript> load(const std::string& path, std::string* error);
  static std::optional<InputScript> parse(const std::string& text, const std::string& name, std::string* error);

  // The input of `frame`: the held state carried over from the previous frame plus this frame's events.
  // `uiTarget` resolves a `ui LABEL` event to the centre of that widget as last drawn.
  template <class Resolve>
  InputFrame frame(uint64_t frame, Resolve&& uiTarget) {
    InputFrame f = carry();
    for (const Event& e : events_)
      if (e.frame == frame) apply(e, f, uiTarget(e.text));
    finish(f);
    return f;
  }
  std::vector<ScriptCommand> commandsAt(uint64_t frame) const;
  uint64_t lastFrame() const { return lastFrame_; }

 private:
  struct Event {
    uint64_t frame = 0;
    enum Kind { Move, Press, Release, KeyDown, KeyUp, Ui } kind = Move;
    glm::dvec2 at{0.0};
    int code = 0;       // button or key
    std::string text;   // ui label
  };
  InputFrame carry() const;
  void apply(const Event& e, InputFrame& f, std::optional<glm::dvec2> uiCentre);
  void finish(InputFrame& f);

  std::vector<Event> events_;
  std::vector<std::pair<uint64_t, ScriptCommand>> commands_;
  uint64_t lastFrame_ = 0;
  InputFrame previous_;
};

// The window's input of this frame (after pollEvents), edges computed against the previous frame.
class WindowInput {
 public:
  InputFrame frame(const platform::Window& window);

 private:
  InputFrame previous_;
};

}  // namespace dyngi::sample
