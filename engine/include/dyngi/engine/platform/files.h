#pragma once
// The rules every path dyngi reads or writes follows (docs/CONTENT.md): inputs are regular files of a
// bounded size; outputs are regular files, character devices (/dev/null) or new files in an existing
// folder, opened without blocking; every write and close is checked. Errors are "<path>: <why>", one line.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dyngi::platform {

constexpr uint64_t kMaxInputBytes = uint64_t(4) << 30;  // a scene, buffer or image file
constexpr size_t kMaxEchoedChars = 240;                 // of one path, value or token in an error line

// "" when `path` is a regular file of at most maxBytes; else why not.
std::string checkInputFile(const std::string& path, uint64_t maxBytes = kMaxInputBytes);
// Reads a file that passes checkInputFile.
std::string readInputFile(const std::string& path, std::vector<uint8_t>& out, uint64_t maxBytes = kMaxInputBytes);

// "" when `path` can be written: an existing regular file or character device, or a new name (each part
// within NAME_MAX) in an existing, writable folder. FIFOs, folders and sockets are refused.
std::string checkOutputPath(const std::string& path);
// Writes `bytes` to `path` (truncating), checking each write and the close: a full disk is an error.
std::string writeOutputFile(const std::string& path, const void* bytes, size_t size);

// An output written over time (a log): opened as writeOutputFile opens, every write checked, the first
// failure kept for close() to report.
class OutputStream {
 public:
  OutputStream() = default;
  ~OutputStream();
  OutputStream(const OutputStream&) = delete;
  OutputStream& operator=(const OutputStream&) = delete;
  std::string open(const std::string& path);
  bool isOpen() const { return fd_ >= 0; }
  void write(std::string_view text);
  std::string close();  // "" or the first error (write or close), naming the path

 private:
  int fd_ = -1;
  std::string path_, error_;
};

// `text` as one line of at most maxChars: control characters and DEL written as \xNN (a newline as \n),
// the middle of an overlong text cut to "...".
std::string oneLine(std::string_view text, size_t maxChars = kMaxEchoedChars);

}  // namespace dyngi::platform
