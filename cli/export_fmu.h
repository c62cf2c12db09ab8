#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace tcpmsim::cli {

struct ExportFmuOptions {
  std::string config;
  std::vector<std::string> overrides;
  std::vector<std::string> outputs;
  std::string output;
  std::string library;  // default: the one installed beside the program, or the build's
  bool quiet = false;
};

// tcpmsim export-fmu SCENARIO -o muscle.fmu [--outputs muscle.force,...] [--library PATH]
CLI::App* add_export_fmu(CLI::App& app, ExportFmuOptions& options);
// Writes the FMU and prints its variables unless quiet; returns 0. Throws as export_fmu does.
int export_fmu(const ExportFmuOptions& options);

}  // namespace tcpmsim::cli
