#include "dyngi/engine/platform/files.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace dyngi::platform {

namespace {
std::string why(const std::string& path, const std::string& reason) { return oneLine(path) + ": " + reason; }

std::string kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISCHR(mode)) return "a character device";
  return "not a regular file";
}

// Output files are opened without blocking (a FIFO with no reader fails at once instead of hanging),
// then checked again as what was opened: a name swapped for a FIFO after the check is still refused.
int openOutput(const std::string& path, std::string& error) {
  if (error = checkOutputPath(path); !error.empty()) return -1;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NONBLOCK | O_CLOEXEC | O_NOCTTY, 0644);
  if (fd < 0) {
    error = why(path, std::string("cannot be opened for writing (") + std::strerror(errno) + ")");
    return -1;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !(S_ISREG(st.st_mode) || S_ISCHR(st.st_mode))) {
    ::close(fd);
    error = why(path, "is " + kindOf(st.st_mode) + ", not a file to write");
    return -1;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

std::string writeAll(int fd, const std::string& path, const char* bytes, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return why(path, std::string("could not be written (") + (n < 0 ? std::strerror(errno) : "no progress") + ")");
    bytes += n;
    size -= size_t(n);
  }
  return {};
}
}  // namespace

std::string checkInputFile(const std::string& path, uint64_t maxBytes) {
  struct stat st {};
  if (path.empty()) return "an empty path";
  if (::stat(path.c_str(), &st) != 0) return why(path, errno == ENOENT ? "file not found" : std::string(std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) return why(path, "is " + kindOf(st.st_mode) + ", not a regular file");
  if (uint64_t(st.st_size) > maxBytes)
    return why(path, "is " + std::to_string(uint64_t(st.st_size) >> 20) + " MiB, over the limit of " + std::to_string(maxBytes >> 20) + " MiB");
  return {};
}

std::string readInputFile(const std::string& path, std::vector<uint8_t>& out, uint64_t maxBytes) {
  if (std::string bad = checkInputFile(path, maxBytes); !bad.empty()) return bad;
  // O_NONBLOCK: a regular file never blocks, and a name swapped for a FIFO since the check does not hang.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return why(path, std::string("cannot be opened (") + std::strerror(errno) + ")");
  struct stat st {};
  std::string error;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || uint64_t(st.st_size) > maxBytes) {
    error = why(path, "changed into something that is not a regular file of bounded size");
  } else {
    out.resize(size_t(st.st_size));
    size_t done = 0;
    while (done < out.size()) {
      const ssize_t n = ::read(fd, out.data() + done, out.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      done += size_t(n);
    }
    if (done != out.size()) error = why(path, "could not be read in full");
  }
  ::close(fd);
  return error;
}

std::string checkOutputPath(const std::string& path) {
  if (path.empty()) return "an empty output path";
  if (path.size() >= PATH_MAX) return why(path, "the path is longer than " + std::to_string(PATH_MAX - 1) + " characters");
  for (size_t begin = 0; begin <= path.size();) {
    const size_t end = std::min(path.find('/', begin), path.size());
    if (end - begin > NAME_MAX) return why(path, "a name in the path is longer than " + std::to_string(NAME_MAX) + " characters");
    begin = end + 1;
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (!(S_ISREG(st.st_mode) || S_ISCHR(st.st_mode))) return why(path, "is " + kindOf(st.st_mode) + ", not a file to write");
    if (::access(path.c_str(), W_OK) != 0) return why(path, "is not writable");
    return {};
  }
  if (errno != ENOENT) return why(path, std::strerror(errno));
  const size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
  if (::stat(folder.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    return why(path, "its folder '" + oneLine(folder) + "' does not exist (it is not created)");
  if (::access(folder.c_str(), W_OK | X_OK) != 0) return why(path, "its folder is not writable");
  return {};
}

std::string writeOutputFile(const std::string& path, const void* bytes, size_t size) {
  std::string error;
  const int fd = openOutput(path, error);
  if (fd < 0) return error;
  error = writeAll(fd, path, static_cast<const char*>(bytes), size);
  if (::close(fd) != 0 && error.empty()) error = why(path, std::string("could not be closed (") + std::strerror(errno) + ")");
  return error;
}

OutputStream::~OutputStream() { close(); }

std::string OutputStream::open(const std::string& path) {
  close();
  path_ = path;
  error_.clear();
  std::string error;
  fd_ = openOutput(path, error);
  return error;
}

void OutputStream::write(std::string_view text) {
  if (fd_ < 0 || !error_.empty()) return;
  error_ = writeAll(fd_, path_, text.data(), text.size());
}

std::string OutputStream::close() {
  if (fd_ < 0) return error_;
  if (::close(fd_) != 0 && error_.empty()) error_ = why(path_, std::string("could not be closed (") + std::strerror(errno) + ")");
  fd_ = -1;
  return error_;
}

namespace {
// A control character as its escape (\n, \xNN), anything else as itself.
void appendEscaped(std::string& out, unsigned char c) {
  if (c == '\n') {
    out += "\\n";
  } else if (c < 0x20 || c == 0x7f) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02x", unsigned(c));
    out += hex;
  } else {
    out += char(c);
  }
}
}  // namespace

std::string oneLine(std::string_view text, size_t maxChars) {
  std::string out;
  out.reserve(std::min(text.size(), maxChars) + 16);
  for (unsigned char c : text) {
    appendEscaped(out, c);
    if (out.size() > 2 * maxChars + 16) break;  // enough for the head's share below
  }
  if (out.size() <= maxChars) return out;
  // Keep the start and the end (a path's file name, a message's reason), cut the middle. The end: the
  // last characters whose escapes fit a third of the length, whatever they are.
  std::string end;
  for (size_t i = text.size(); i > 0; --i) {
    std::string e;
    appendEscaped(e, static_cast<unsigned char>(text[i - 1]));
    if (end.size() + e.size() > maxChars / 3) break;
    end.insert(0, e);
  }
  const size_t headChars = maxChars > end.size() + 3 ? maxChars - end.size() - 3 : 0;
  return out.substr(0, headChars) + "..." + end;
}

}  // namespace dyngi::platform
