#include "fuzz/fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>

#include "sim/config/config_error.h"
#include "sim/config/units.h"
#include "sim/parameters.h"

namespace tcpmsim::fuzz {

void expect_clean_outcome(const std::function<void()>& parse) {
  try {
    parse();
  } catch (const ConfigError&) {
  } catch (const UnitError&) {
  } catch (const ParameterError&) {
  } catch (const UsageError&) {
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fuzz: an input reached the user as an internal error: %s\n",
                 error.what());
    std::abort();
  }
}

std::string text_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

std::string scratch_directory(const std::string& name, const std::string& source_folder) {
  namespace fs = std::filesystem;
  const fs::path directory =
      fs::temp_directory_path() / ("tcpmsim_fuzz_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(directory);
  fs::create_directories(directory);
  for (const auto& entry : fs::directory_iterator(fs::path(TCPMSIM_SOURCE_DIR) / source_folder))
    fs::create_symlink(entry.path(), directory / entry.path().filename());
  return directory.string();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

}  // namespace tcpmsim::fuzz
