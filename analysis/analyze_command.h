#pragma once

#include <ostream>
#include <string>

#include "analysis/record_analysis.h"
#include "sim/io/hdf5_writer.h"

namespace tcpmsim {

struct AnalyzeOptions {
  std::string record;  // the HDF5 record analysed
  AnalysisRequest request;
  std::string output;      // HDF5; empty: default_analysis_path
  std::string invocation;  // the command line, for the file's provenance
  bool quiet = false;
};

// The output of an analysis without -o: results/<record stem>_<response>_analysis.h5 (the
// response's '/' as '_'), or _steps.h5 for step metrics (--reference), so that two analyses
// of one record do not overwrite each other.
std::string default_analysis_path(const std::string& record, const AnalysisRequest& request);

// `tcpmsim analyze`: analyses the record as asked, prints the report and writes the analysis
// (write_record_analysis). Returns the output path.
std::string run_analyze_command(const AnalyzeOptions& options, std::ostream& out);

// The analysis into `file`: /steps/<metric> (one value per step) and
// /frequency_response/<input, its / as .>/{frequency, magnitude (dB), magnitude_ratio, phase,
// real, imag, radius_95, coherence, bandwidth}, each with units; the window, method and notes as
// attributes.
void write_record_analysis(Hdf5Writer& file, const RecordAnalysis& analysis);

}  // namespace tcpmsim
