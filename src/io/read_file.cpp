// Reading an input file: a regular file or a pipe of bounded size, never a device or an idle FIFO;
// then TOML or the paper's .inp by its content.
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "whatnext/config.hpp"

namespace whatnext {

namespace {

// How long a pipe (a FIFO, or `<(command)`) may keep whatnext waiting for its first byte: a FIFO
// that nobody writes into would otherwise block it for ever.
constexpr int kPipeWaitMs = 5000;

// Reads at most kMaxInputBytes from a regular file or a pipe: a directory, a device (/dev/null,
// /dev/zero, a terminal) or a huge file is refused at once, an idle pipe after kPipeWaitMs.
std::string read_file(const std::string& path) {
  const std::string shown = printable(path, 96);
  // Non-blocking, so that opening a FIFO without a writer returns at once.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    throw InputError(fmt::format("{}: cannot read the input file: {}", shown, std::strerror(errno)));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    throw InputError(fmt::format("{}: cannot read the input file: {}", shown, std::strerror(errno)));
  }
  if (S_ISDIR(st.st_mode)) throw InputError(fmt::format("{}: is a directory, not an input file", shown));
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) {
    throw InputError(
        fmt::format("{}: is a device, not an input file (give a machine's TOML or .inp file)", shown));
  }
  if (S_ISFIFO(st.st_mode)) {
    pollfd p{fd, POLLIN, 0};
    int ready = 0;
    do {
      ready = ::poll(&p, 1, kPipeWaitMs);
    } while (ready < 0 && errno == EINTR);
    if (ready == 0) {
      throw InputError(fmt::format("{}: a pipe that nothing was written into within {} s; nothing to read",
                                   shown, kPipeWaitMs / 1000));
    }
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  const auto too_big = [&] {
    return InputError(
        fmt::format("{}: an input file has at most {} bytes; this one has more", shown, kMaxInputBytes));
  };
  if (S_ISREG(st.st_mode) && static_cast<std::uintmax_t>(st.st_size) > kMaxInputBytes) throw too_big();
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0)
      throw InputError(fmt::format("{}: cannot read the input file: {}", shown, std::strerror(errno)));
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > kMaxInputBytes) throw too_big();
  }
  return text;
}

}  // namespace

Config load_config_file(const std::string& path) {
  const std::string text = read_file(path);
  // Past a UTF-8 byte order mark: a .inp saved with one still starts with a number.
  const auto first = text.find_first_not_of(" \t\r\n", text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0);
  const bool looks_inp =
      (path.size() >= 4 && path.compare(path.size() - 4, 4, ".inp") == 0) ||
      (first != std::string::npos && (std::isdigit(static_cast<unsigned char>(text[first])) ||
                                      text[first] == '-' || text[first] == '+' || text[first] == '.'));
  return looks_inp ? parse_inp(text, path) : parse_toml(text, path);
}

}  // namespace whatnext
