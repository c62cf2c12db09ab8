#include "fmu/fmu_export.h"

#include <unistd.h>
#include <zip.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "fmu/fmu_resources.h"
#include "fmu/model_description.h"
#include "kinds/standard_kinds.h"
#include "sim/config/config_error.h"
#include "sim/io/hdf5_files.h"

namespace tcpmsim::fmu {
namespace {

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// A directory removed with everything in it when the export ends.
struct ScratchDirectory {
  std::filesystem::path path;
  explicit ScratchDirectory(const std::string& near) {
    const auto parent = std::filesystem::absolute(near).parent_path();
    for (int attempt = 0;; ++attempt) {
      path = parent / (".fmu-export-" + std::to_string(::getpid()) + "-" + std::to_string(attempt));
      if (std::filesystem::create_directory(path)) break;
      if (attempt > 100)
        throw std::runtime_error("cannot make a scratch directory in " + parent.string());
    }
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

class ZipWriter {
 public:
  explicit ZipWriter(const std::string& path) : path_(path) {
    int error = 0;
    archive_ = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    if (!archive_) {
      zip_error_t problem;
      zip_error_init_with_code(&problem, error);
      const std::string message = zip_error_strerror(&problem);
      zip_error_fini(&problem);
      throw std::runtime_error("cannot create " + path + ": " + message);
    }
  }
  ~ZipWriter() {
    if (archive_) zip_discard(archive_);
  }
  void add_file(const std::string& name, const std::string& file) {
    zip_source_t* source = zip_source_file(archive_, file.c_str(), 0, -1);
    if (!source || zip_file_add(archive_, name.c_str(), source, ZIP_FL_ENC_UTF_8) < 0) {
      if (source) zip_source_free(source);
      fail("cannot add " + name);
    }
  }
  void close() {
    if (zip_close(archive_) < 0) fail("cannot write the archive");
    archive_ = nullptr;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error(path_ + ": " + what + ": " + zip_strerror(archive_));
  }
  std::string path_;
  zip_t* archive_ = nullptr;
};

}  // namespace

FmuInterface export_fmu(const FmuExportRequest& request, std::shared_ptr<const UnitSystem> units) {
  if (!std::filesystem::is_regular_file(request.library))
    throw UsageError("--library: no FMU library at " + request.library +
                     " (build the target tcpmsim_fmu, or give --library)");
  check_output_path(request.output);  // before any work, as every command's output
  const Scenario scenario = load_scenario(request.scenario_file, request.overrides, units);
  if (!scenario.parameter_settings.empty()) {
    // A --set of a parameter lives in the run context, not in the resolved YAML the FMU carries.
    std::string paths;
    for (const auto& [path, value] : scenario.parameter_settings) paths += " " + path;
    throw UsageError("--set of model parameters (" + paths.substr(1) +
                     ") is not carried into an FMU: its parameters are the FMU's own "
                     "(set them from the master), or write the value into the scenario");
  }
  FmuSettings settings{model_identifier_for(scenario.settings.name), request.outputs};

  const ScratchDirectory scratch(request.output);
  const auto resources = scratch.path / "resources";
  const auto binaries = scratch.path / "binaries" / "linux64";
  std::filesystem::create_directories(resources);
  std::filesystem::create_directories(binaries);
  write_text(resources / kScenarioResource, scenario.resolved_yaml);
  write_text(resources / kSettingsResource, settings_yaml(settings));
  // The interface as the library will make it from the same files. The scenario loaded where it
  // lies; from the resources it fails only on a file it names by a relative path.
  const FmuResources packed = [&] {
    try {
      return read_fmu_resources(resources.string(), units);
    } catch (const ConfigError&) {
      throw UsageError(request.scenario_file +
                       ": it reads a file by a relative path (a measurement or a data signal), "
                       "which the FMU does not carry: scenarios that read other files do not "
                       "export yet");
    }
  }();
  const FmuInterface fmu =
      fmu_interface(packed.scenario, packed.settings.outputs, packed.settings.model_identifier);
  const std::string description = model_description_xml(fmu, *units, request.tool, utc_now());
  const auto problems = model_description_problems(description);
  if (!problems.empty()) {
    std::string all;
    for (const auto& problem : problems) all += "\n  " + problem;
    throw std::logic_error("the modelDescription.xml made breaks FMI 2.0's rules:" + all);
  }
  write_text(scratch.path / "modelDescription.xml", description);

  const auto partial = scratch.path / "partial.fmu";
  ZipWriter zip(partial.string());
  zip.add_file("modelDescription.xml", (scratch.path / "modelDescription.xml").string());
  zip.add_file("binaries/linux64/" + fmu.model_identifier + ".so", request.library);
  zip.add_file(std::string("resources/") + kScenarioResource,
               (resources / kScenarioResource).string());
  zip.add_file(std::string("resources/") + kSettingsResource,
               (resources / kSettingsResource).string());
  zip.close();
  std::filesystem::rename(partial, request.output);
  return fmu;
}

}  // namespace tcpmsim::fmu
