#include "sweep/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace tcpmsim::sweep {

FileLock::FileLock(const std::string& path, Mode mode) {
  descriptor_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (descriptor_ < 0)
    throw std::runtime_error("cannot open the lock file " + path + ": " + std::strerror(errno));
  const int operation = (mode == Mode::exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB;
  int result = 0;
  do {
    result = ::flock(descriptor_, operation);
  } while (result != 0 && errno == EINTR);
  taken_ = result == 0 || (errno != EWOULDBLOCK && errno != EAGAIN);
}

FileLock::~FileLock() {
  release();
}

void FileLock::release() {
  if (descriptor_ >= 0) ::close(descriptor_);  // releases the lock
  descriptor_ = -1;
  taken_ = false;
}

FileLock::FileLock(FileLock&& other) noexcept
    : descriptor_(std::exchange(other.descriptor_, -1)),
      taken_(std::exchange(other.taken_, false)) {}

FileLock& FileLock::operator=(FileLock&& other) noexcept {
  if (this != &other) {
    release();
    descriptor_ = std::exchange(other.descriptor_, -1);
    taken_ = std::exchange(other.taken_, false);
  }
  return *this;
}

}  // namespace tcpmsim::sweep
