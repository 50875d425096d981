#include "play/input.h"

#include <GLFW/glfw3.h>

#include <fstream>
#include <sstream>

#include "dyngi/engine/platform/files.h"
#include "dyngi/engine/platform/window.h"

namespace dyngi::sample {
namespace {

// Every key the sample reads, by the name a script writes.
const std::vector<std::pair<std::string, int>>& keyNames() {
  static const std::vector<std::pair<std::string, int>> names = [] {
    std::vector<std::pair<std::string, int>> v;
    for (char c = 'A'; c <= 'Z'; ++c) v.push_back({std::string(1, c), GLFW_KEY_A + (c - 'A')});
    for (char c = '0'; c <= '9'; ++c) v.push_back({std::string(1, c), GLFW_KEY_0 + (c - '0')});
    for (int i = 1; i <= 12; ++i) {
      std::string name = "F";
      name += std::to_string(i);  // not "F" + to_string: GCC 12's -Wrestrict misfires on that
      v.push_back({name, GLFW_KEY_F1 + (i - 1)});
    }
    v.insert(v.end(), {{"DELETE", GLFW_KEY_DELETE}, {"SPACE", GLFW_KEY_SPACE}, {"ESCAPE", GLFW_KEY_ESCAPE}, {"EQUAL", GLFW_KEY_EQUAL},
                       {"MINUS", GLFW_KEY_MINUS}, {"TAB", GLFW_KEY_TAB}, {"ENTER", GLFW_KEY_ENTER}, {"SHIFT", GLFW_KEY_LEFT_SHIFT},
                       {"CONTROL", GLFW_KEY_LEFT_CONTROL}});
    return v;
  }();
  return names;
}

std::optional<int> keyCode(const std::string& name) {
  for (const auto& [n, code] : keyNames())
    if (n == name) return code;
  return std::nullopt;
}

std::optional<int> buttonCode(const std::string& name) {
  if (name == "left") return kLeft;
  if (name == "right") return kRight;
  if (name == "middle") return kMiddle;
  return std::nullopt;
}

}  // namespace

std::optional<InputScript> InputScript::load(const std::string& path, std::string* error) {
  std::vector<uint8_t> bytes;
  if (std::string bad = platform::readInputFile(path, bytes, kMaxScriptBytes); !bad.empty()) {
    *error = bad + " (the input script)";
    return std::nullopt;
  }
  return parse(std::string(bytes.begin(), bytes.end()), path, error);
}

std::optional<InputScript> InputScript::parse(const std::string& text, const std::string& name, std::string* error) {
  InputScript s;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  auto fail = [&](const std::string& why) {
    *error = platform::oneLine(name) + ":" + std::to_string(number) + ": " + platform::oneLine(why);
    return std::nullopt;
  };
  constexpr double kMaxCoordinate = 1 << 16;
  constexpr uint64_t kMaxFrame = 10'000'000;
  while (std::getline(lines, line)) {
    ++number;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream in(line);
    std::string frameText, verb;
    if (!(in >> frameText)) continue;  // blank
    uint64_t frame = 0;
    try {
      size_t used = 0;
      const long long v = std::stoll(frameText, &used);
      if (used != frameText.size() || v < 0 || uint64_t(v) > kMaxFrame) return fail("a frame number 0.." + std::to_string(kMaxFrame) + " first");
      frame = uint64_t(v);
    } catch (...) {
      return fail("a frame number first, not '" + frameText + "'");
    }
    if (!(in >> verb)) return fail("an event after the frame number");
    auto point = [&](glm::dvec2& p) {
      return bool(in >> p.x >> p.y) && std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate;
    };
    auto push = [&](uint64_t at, Event::Kind kind, glm::dvec2 p = {}, int code = 0, std::string label = {}) {
      s.events_.push_back({at, kind, p, code, std::move(label)});
      s.lastFrame_ = std::max(s.lastFrame_, at);
    };
    std::string word;
    glm::dvec2 a, b;
    if (verb == "move") {
      if (!point(a)) return fail("move X Y");
      push(frame, Event::Move, a);
    } else if (verb == "press" || verb == "release") {
      std::optional<int> button;
      if (!(in >> word) || !(button = buttonCode(word))) return fail(verb + " left|right|middle");
      push(frame, verb == "press" ? Event::Press : Event::Release, {}, *button);
    } else if (verb == "click") {
      if (!point(a)) return fail("click X Y");
      push(frame, Event::Move, a);
      push(frame, Event::Press, {}, kLeft);
      push(frame + 1, Event::Release, {}, kLeft);
    } else if (verb == "drag") {
      int steps = 0;
      if (!point(a) || !point(b) || !(in >> steps) || steps < 1 || steps > 10000) return fail("drag X0 Y0 X1 Y1 N (N: 1..10000 frames)");
      push(frame, Event::Move, a);
      push(frame, Event::Press, {}, kLeft);
      for (int i = 1; i <= steps; ++i) push(frame + uint64_t(i), Event::Move, a + (b - a) * (double(i) / steps));
      push(frame + uint64_t(steps) + 1, Event::Release, {}, kLeft);
    } else if (verb == "key" || verb == "hold" || verb == "unhold") {
      std::optional<int> key;
      if (!(in >> word) || !(key = keyCode(word))) return fail(verb + " NAME (A-Z, 0-9, F1-F12, DELETE, SPACE, ESCAPE, EQUAL, MINUS, TAB, ENTER, SHIFT, CONTROL)");
      if (verb != "unhold") push(frame, Event::KeyDown, {}, *key);
      if (verb == "key") push(frame + 1, Event::KeyUp, {}, *key);
      if (verb == "unhold") push(frame, Event::KeyUp, {}, *key);
    } else if (verb == "ui") {
      std::getline(in, word);
      const size_t start = word.find_first_not_of(" \t");
      if (start == std::string::npos) return fail("ui LABEL");
      word = word.substr(start, word.find_last_not_of(" \t\r") - start + 1);
      push(frame, Event::Ui, {}, 0, word);
      push(frame + 1, Event::Release, {}, kLeft);
    } else if (verb == "screenshot") {
      if (!(in >> word)) return fail("screenshot FILE.png");
      if (std::string bad = platform::checkOutputPath(word); !bad.empty()) return fail("screenshot " + bad);
      s.commands_.push_back({frame, {ScriptCommand::Screenshot, word}});
      s.lastFrame_ = std::max(s.lastFrame_, frame);
    } else if (verb == "resize") {
      uint32_t w = 0, h = 0;
      if (!(in >> w >> h) || w < 1 || h < 1 || w > 8192 || h > 8192) return fail("resize W H (1..8192 each)");
      s.commands_.push_back({frame, {ScriptCommand::Resize, {}, {w, h}}});
      s.lastFrame_ = std::max(s.lastFrame_, frame);
    } else if (verb == "quit") {
      s.commands_.push_back({frame, {ScriptCommand::Quit, {}}});
      s.lastFrame_ = std::max(s.lastFrame_, frame);
    } else {
      return fail("unknown event '" + verb + "' (move, press, release, click, drag, key, hold, unhold, ui, screenshot, resize, quit)");
    }
    if (in >> word) return fail("unexpected '" + word + "' at the end of the line");
  }
  return s;
}

InputFrame InputScript::carry() const {
  InputFrame f;
  f.mouse = previous_.mouse;
  for (int b = 0; b < 3; ++b) f.down[b] = previous_.down[b];
  f.keysDown = previous_.keysDown;
  return f;
}

void InputScript::apply(const Event& e, InputFrame& f, std::optional<glm::dvec2> uiCentre) {
  switch (e.kind) {
    case Event::Move: f.mouse = e.at; break;
    case Event::Press: f.down[e.code] = true; break;
    case Event::Release: f.down[e.code] = false; break;
    case Event::KeyDown: f.keysDown.insert(e.code); break;
    case Event::KeyUp: f.keysDown.erase(e.code); break;
    case Event::Ui:
      // A widget not drawn (yet) gets no click: the script's check on the panel then fails visibly.
      if (uiCentre) {
        f.mouse = *uiCentre;
        f.down[kLeft] = true;
      }
      break;
  }
}

void InputScript::finish(InputFrame& f) {
  if (previous_.mouse.x >= 0 && f.mouse.x >= 0) f.mouseDelta = f.mouse - previous_.mouse;
  for (int b = 0; b < 3; ++b) {
    f.pressed[b] = f.down[b] && !previous_.down[b];
    f.released[b] = !f.down[b] && previous_.down[b];
  }
  for (int k : f.keysDown)
    if (!previous_.keysDown.count(k)) f.keysPressed.insert(k);
  previous_ = f;
}

std::vector<ScriptCommand> InputScript::commandsAt(uint64_t frame) const {
  std::vector<ScriptCommand> out;
  for (const auto& [at, c] : commands_)
    if (at == frame) out.push_back(c);
  return out;
}

InputFrame WindowInput::frame(const platform::Window& window) {
  InputFrame f;
  window.cursorPosition(f.mouse.x, f.mouse.y);
  double dx = 0, dy = 0;
  window.mouseDelta(dx, dy);
  f.mouseDelta = {dx, dy};
  f.scroll = window.scrollDelta();
  for (int b = 0; b < 3; ++b) {
    f.down[b] = window.mouseButtonDown(b);
    f.pressed[b] = f.down[b] && !previous_.down[b];
    f.released[b] = !f.down[b] && previous_.down[b];
  }
  for (const auto& [name, code] : keyNames())
    if (window.keyDown(code)) {
      f.keysDown.insert(code);
      if (!previous_.keysDown.count(code)) f.keysPressed.insert(code);
    }
  previous_ = f;
  return f;
}

}  // namespace dyngi::sample
