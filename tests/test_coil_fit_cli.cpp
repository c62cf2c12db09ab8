// `tcpmsim coil-fit` end to end: the binary next to the tests' build directory runs the
// analysis, prints both tables, writes the HDF5 file, and reports bad input with exit codes.
#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <H5Cpp.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/support/test_support.h"

using tcpmsim::testing::source_path;

namespace {

namespace fs = std::filesystem;

// The tcpmsim binary of this build: tests/tcpmsim_tests -> ../tcpmsim.
fs::path binary() {
  return fs::canonical("/proc/self/exe").parent_path().parent_path() / "tcpmsim";
}

struct Outcome {
  int exit_code = -1;
  std::string out, err;
};

Outcome run(const std::string& arguments, const fs::path& work) {
  // Built by appending: GCC 12 reports a false -Wrestrict for a long operator+ chain here.
  std::string command = "'";
  command.append(binary().string()).append("' ").append(arguments);
  command.append(" >'").append((work / "out").string()).append("'");
  command.append(" 2>'").append((work / "err").string()).append("'");
  const int status = std::system(command.c_str());
  Outcome outcome;
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::stringstream out, err;
  out << std::ifstream(work / "out").rdbuf();
  err << std::ifstream(work / "err").rdbuf();
  outcome.out = out.str();
  outcome.err = err.str();
  return outcome;
}

std::string springs() {
  std::string list;
  for (const char* name : {"s1", "s2", "s3", "s4"}) {
    list += " '" + source_path(std::string("configs/springs/") + name + ".yaml") + "'";
  }
  return list;
}

}  // namespace

TEST_CASE("tcpmsim coil-fit prints Tables 2.2 and 2.3 and writes them to HDF5") {
  REQUIRE(fs::exists(binary()));
  const fs::path work =
      fs::temp_directory_path() / ("tcpmsim_coil_fit_cli_" + std::to_string(getpid()));
  fs::create_directories(work);
  const std::string data = source_path("data/coil-spring-inductance");
  const Outcome outcome =
      run("coil-fit" + springs() + " --data '" + data + "' -o '" + (work / "fit.h5").string() + "'",
          work);
  INFO(outcome.out << outcome.err);
  CHECK(outcome.exit_code == 0);
  CHECK(outcome.out.find("Thesis Table 2.2") != std::string::npos);
  CHECK(outcome.out.find("Thesis Table 2.3") != std::string::npos);
  CHECK(outcome.out.find("S1_01 S1-a") != std::string::npos);
  REQUIRE(fs::exists(work / "fit.h5"));
  CHECK_FALSE(fs::exists(work / "fit.h5.partial"));

  H5::H5File file((work / "fit.h5").string(), H5F_ACC_RDONLY);
  H5::DataSet table = file.openDataSet("/tables/rmse_percent");
  hsize_t dimensions[2] = {0, 0};
  table.getSpace().getSimpleExtentDims(dimensions);
  CHECK(dimensions[0] == 8);
  CHECK(dimensions[1] == 7);
  H5::DataSet deflection = file.openDataSet("/S1_01/deflection");
  std::string units;
  H5::Attribute attribute = deflection.openAttribute("units");
  attribute.read(attribute.getStrType(), units);
  CHECK(units == "m");
  CHECK(file.nameExists("/chapter3/S4_01/resistance/slope"));
  file.close();
  fs::remove_all(work);
}

TEST_CASE("tcpmsim coil-fit reports a bad data line with its location and exit code 3") {
  const fs::path work =
      fs::temp_directory_path() / ("tcpmsim_coil_fit_cli_bad_" + std::to_string(getpid()));
  fs::create_directories(work / "data");
  const std::string data = source_path("data/coil-spring-inductance");
  for (const char* name : {"S2_01"}) {
    std::ifstream in(fs::path(data) / (std::string(name) + ".csv"));
    std::stringstream text;
    text << in.rdbuf();
    std::string content = text.str();
    const auto second_line = content.find('\n') + 1;
    content.replace(content.find("; ", second_line), 2, ";; ");  // an extra empty field
    std::ofstream(work / "data" / (std::string(name) + ".csv")) << content;
  }
  const Outcome outcome =
      run("coil-fit '" + source_path("configs/springs/s2.yaml") + "' --data '" +
              (work / "data").string() + "' -o '" + (work / "fit.h5").string() + "'",
          work);
  CHECK(outcome.exit_code == 3);
  CHECK(outcome.err.find("S2_01.csv:2:") != std::string::npos);
  CHECK(outcome.err.find("error: expected 24 fields separated by ';'") != std::string::npos);
  CHECK_FALSE(fs::exists(work / "fit.h5"));
  // A data directory that does not exist is a usage error.
  CHECK(run("coil-fit '" + source_path("configs/springs/s2.yaml") + "' --data '" +
                (work / "none").string() + "'",
            work)
            .exit_code == 2);
  fs::remove_all(work);
}
