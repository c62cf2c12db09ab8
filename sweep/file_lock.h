#pragma once

#include <string>

namespace tcpmsim::sweep {

// An advisory lock on a file (flock(2)), taken without waiting and held while the object lives.
// The system drops it when the holder ends, however it ends (SIGKILL included), so a lock that
// is held names a live process. Where flock fails for another reason than a conflict (a file
// system without locks: ENOLCK, EOPNOTSUPP, ENOSYS) nothing can be checked, and the lock counts
// as taken.
class FileLock {
 public:
  enum class Mode { shared, exclusive };
  FileLock() = default;
  // Creates the file if it is missing. Throws std::runtime_error if it cannot be opened.
  FileLock(const std::string& path, Mode mode);
  ~FileLock();
  FileLock(FileLock&& other) noexcept;
  FileLock& operator=(FileLock&& other) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

  // False if another holder's lock on the file conflicted with this one.
  bool taken() const { return taken_; }
  // Lets go of the lock and closes the file (also done by the destructor).
  void release();

 private:
  int descriptor_ = -1;
  bool taken_ = false;
};

}  // namespace tcpmsim::sweep
