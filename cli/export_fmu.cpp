#include "cli/export_fmu.h"

#include <filesystem>
#include <iostream>
#include <memory>

#include "fmu/fmu_export.h"
#include "sim/value_check.h"
#include "tcpmsim/version.h"

namespace tcpmsim::cli {
namespace {

// The FMU library beside an installed program (<prefix>/bin/tcpmsim and
// <prefix>/<libdir>/tcpmsim/tcpmsim_fmu.so), else the build tree's.
std::string default_library() {
  std::error_code error;
  const auto program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const auto installed = program.parent_path().parent_path() / TCPMSIM_FMU_LIBRARY_INSTALL;
    if (std::filesystem::is_regular_file(installed)) return installed.string();
  }
#ifdef TCPMSIM_FMU_LIBRARY_BUILD
  return TCPMSIM_FMU_LIBRARY_BUILD;
#else
  return "(not built in this tree: configure without sanitizers)";
#endif
}

}  // namespace

CLI::App* add_export_fmu(CLI::App& app, ExportFmuOptions& options) {
  CLI::App* command = app.add_subcommand(
      "export-fmu",
      "Write an FMI 2.0 co-simulation FMU of a scenario with external inputs (Simulink, "
      "OpenModelica, FMPy)");
  command
      ->add_option("config", options.config,
                   "Scenario file (YAML) with a controller of type external")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option(
          "--set", options.overrides,
          "Override a value of the scenario (not a model parameter: those are the FMU's own)")
      ->type_name("KEY.PATH=VALUE");
  command->add_option("-o,--output", options.output, "The FMU to write (.fmu)")->required();
  command
      ->add_option("--outputs", options.outputs,
                   "The outputs the FMU exposes, group.name (default: every recorded output)")
      ->delimiter(',');
  command->add_option("--library", options.library,
                      "The FMU library to pack (default: tcpmsim_fmu.so of this installation)");
  command->add_flag("-q,--quiet", options.quiet, "No listing");
  return command;
}

int export_fmu(const ExportFmuOptions& options) {
  fmu::FmuExportRequest request;
  request.scenario_file = options.config;
  request.overrides = options.overrides;
  request.outputs = options.outputs;
  request.output = options.output;
  request.library = options.library.empty() ? default_library() : options.library;
  request.tool = std::string("tcpmsim ") + kVersion + " (" + kGitCommit + ")";
  const fmu::FmuInterface fmu = fmu::export_fmu(request, std::make_shared<const UnitSystem>());
  if (!options.quiet) {
    std::cout << "wrote " << options.output << ": FMI 2.0 co-simulation, model "
              << fmu.model_identifier << ", guid " << fmu.guid << ", stop time "
              << number_text(fmu.stop_time) << " s; library " << request.library << "\n";
    int parameters = 0;
    for (const auto& variable : fmu.variables) {
      using C = fmu::FmuVariable::Causality;
      if (variable.causality == C::parameter) {
        ++parameters;
        continue;
      }
      std::cout << "  " << (variable.causality == C::input ? "input " : "output") << "  vr "
                << variable.value_reference << "  " << variable.name << " [" << variable.unit
                << "]";
      if (variable.causality == C::input)
        std::cout << " start " << number_text(variable.start) << ", range ["
                  << number_text(variable.min) << ", " << number_text(variable.max) << "]";
      std::cout << "\n";
    }
    std::cout << "  and " << parameters << " parameters (fixed: set them before "
              << "fmi2ExitInitializationMode)\n";
  }
  return 0;
}

}  // namespace tcpmsim::cli
