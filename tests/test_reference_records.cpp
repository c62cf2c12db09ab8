// Refactors prove themselves: every shipped scenario, and each thesis analysis, writes a record
// bit-identical to the one pinned in tests/reference/records.digest. The digest was made from the
// records of commit a5ee02a (the last commit before the composition refactor) with
// build/tests/record_digest; an issue that changes results on purpose regenerates it and says so.
// Issue 14 added entries only: the units of /inputs arrays, and the configs and seeds of the
// three analyses' files (their command line and config paths, like the records', are not pinned).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "analysis/coil_fit_command.h"
#include "analysis/control_tasks_command.h"
#include "analysis/spring_forces_command.h"
#include "sim/run.h"
#include "tests/support/record_digest.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

std::map<std::string, RecordDigest> reference_digests() {
  std::ifstream file(source_path("tests/reference/records.digest"));
  std::stringstream text;
  text << file.rdbuf();
  std::map<std::string, RecordDigest> sections;
  std::string line, name, body;
  std::istringstream lines(text.str());
  auto close = [&] {
    if (!name.empty()) sections[name] = parse_digest(body);
    body.clear();
  };
  while (std::getline(lines, line)) {
    if (line.rfind("== ", 0) == 0) {
      close();
      name = line.substr(3);
    } else {
      body += line + "\n";
    }
  }
  close();
  return sections;
}

// Every entry that differs, is missing or is new, for a readable failure.
std::string differences(const RecordDigest& expected, const RecordDigest& actual) {
  std::string report;
  for (const auto& [path, hash] : expected) {
    const auto found = actual.find(path);
    if (found == actual.end()) {
      report += "  missing " + path + "\n";
    } else if (found->second != hash) {
      report += "  differs " + path + "\n";
    }
  }
  for (const auto& [path, hash] : actual) {
    if (!expected.count(path)) report += "  new     " + path + "\n";
  }
  return report;
}

// Named by process too: two builds' suites may run at once.
std::string temporary(const std::string& name) {
  const std::string file = "tcpmsim_reference_" + std::to_string(::getpid()) + "_" + name + ".h5";
  return (std::filesystem::temp_directory_path() / file).string();
}

void check_record(const std::map<std::string, RecordDigest>& reference, const std::string& name,
                  const std::string& path) {
  INFO(name);
  REQUIRE(reference.count(name) == 1);
  const RecordDigest actual = record_digest(path);
  std::filesystem::remove(path);
  CHECK(differences(reference.at(name), actual) == "");
}

}  // namespace

TEST_CASE("Every shipped scenario writes the record pinned before the composition refactor") {
  // The scenarios that existed then: each pinned section names one, "ch7_control__force_steps"
  // for configs/ch7_control/force_steps.yaml. Scenarios added since are not pinned.
  const auto reference = reference_digests();
  int count = 0;
  for (const auto& [name, digest] : reference) {
    if (name == "coil_fit" || name == "spring_forces" || name == "control_tasks") continue;
    const auto split = name.find("__");
    std::filesystem::path file = source_path("configs");
    if (split == std::string::npos) {
      file /= name + ".yaml";
    } else {
      file /= name.substr(0, split);
      file /= name.substr(split + 2) + ".yaml";
    }
    Scenario scenario = load_scenario(file.string(), {}, shared_units());
    const std::string output = temporary(name);
    REQUIRE(run_scenario(scenario, output).succeeded);
    check_record(reference, name, output);
    ++count;
  }
  CHECK(count == 18);
}

TEST_CASE("The three thesis analyses write the records pinned before the composition refactor") {
  const auto reference = reference_digests();
  std::ostringstream ignored;
  {
    analysis::CoilFitOptions options;
    for (const char* spring : {"s1", "s2", "s3", "s4"})
      options.spring_files.push_back(
          source_path(std::string("configs/springs/") + spring + ".yaml"));
    options.data_directory = source_path("data/coil-spring-inductance");
    options.output = temporary("coil_fit");
    options.quiet = true;
    analysis::run_coil_fit(options, ignored, shared_units());
    check_record(reference, "coil_fit", options.output);
  }
  {
    SpringForcesOptions options;
    for (const auto& entry : std::filesystem::directory_iterator(source_path("configs/ch4")))
      options.configs.push_back(entry.path().string());
    std::sort(options.configs.begin(), options.configs.end());
    options.output = temporary("spring_forces");
    options.quiet = true;
    run_spring_forces_command(options, ignored, shared_units());
    check_record(reference, "spring_forces", options.output);
  }
  {
    ControlTasksOptions options;
    for (const char* task : {"deflection_steps", "deflection_sweep", "force_steps", "force_sweep"})
      options.configs.push_back(source_path(std::string("configs/ch7_control/") + task + ".yaml"));
    options.output = temporary("control_tasks");
    options.quiet = true;
    run_control_tasks_command(options, ignored, shared_units());
    check_record(reference, "control_tasks", options.output);
  }
}
