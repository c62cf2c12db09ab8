#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

namespace {

// A run that passed removes the scratch directories of its process, "<name>_<pid>" under
// <temp>/tcpmsim_tests (tests/support/test_support.h: process_directory): ctest starts a process
// per test case, and their data would otherwise pile up, hundreds of megabytes a suite. A run
// that failed keeps them to be looked at.
class ProcessDirectoryCleanup : public Catch::TestEventListenerBase {
 public:
  using Catch::TestEventListenerBase::TestEventListenerBase;

  void testRunEnded(Catch::TestRunStats const& stats) override {
    Catch::TestEventListenerBase::testRunEnded(stats);
    if (stats.totals.assertions.failed > 0 || stats.totals.testCases.failed > 0) return;
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::path root = fs::temp_directory_path(error) / "tcpmsim_tests";
    if (error || !fs::is_directory(root, error)) return;
    const std::string suffix = "_" + std::to_string(::getpid());
    for (const auto& entry : fs::directory_iterator(root, error)) {
      const std::string name = entry.path().filename().string();
      if (name.size() > suffix.size() && name.ends_with(suffix))
        fs::remove_all(entry.path(), error);
    }
  }
};

}  // namespace

CATCH_REGISTER_LISTENER(ProcessDirectoryCleanup)
