// Prints the digest of HDF5 files (tests/support/record_digest.h), one "== file" section each:
// how tests/reference/records.digest is made from a trusted build's records.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>

#include "tests/support/record_digest.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: record_digest FILE.h5...\n";
    return 2;
  }
  try {
    for (int i = 1; i < argc; ++i) {
      std::cout << "== " << std::filesystem::path(argv[i]).stem().string() << "\n"
                << tcpmsim::testing::format_digest(tcpmsim::testing::record_digest(argv[i]));
    }
  } catch (const std::exception& error) {
    std::cerr << "record_digest: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
