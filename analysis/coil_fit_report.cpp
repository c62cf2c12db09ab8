#include "analysis/coil_fit_report.h"

#include <sstream>

#include <fstream>

#include <cmath>
#include <cstdio>
#include <limits>

#include "analysis/thesis_tables.h"
#include "sim/io/hdf5_writer.h"

namespace tcpmsim::analysis {

namespace {

std::string format(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string pad(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : text + std::string(width - text.size(), ' ');
}

std::string pad_left(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : std::string(width - text.size(), ' ') + text;
}

// The thesis column a result column is compared with (Rosa* against the published Rosa).
int thesis_column(const std::string& key) {
  if (key == "basic") return kBasic;
  if (key == "nagaoka") return kNagaoka;
  if (key == "rosa" || key == "rosa_published") return kRosa;
  if (key == "maxwell") return kMaxwell;
  if (key == "neumann_helix") return kHelix;
  return kFitted;
}

double published(const std::string& sequence, const std::string& key, bool r_squared) {
  const auto row = thesis_row(sequence);
  if (!row) return std::numeric_limits<double>::quiet_NaN();
  const int column = thesis_column(key);
  return r_squared ? row->r_squared[column] : row->rmse_percent[column];
}

std::string label(const SequenceAnalysis& a) {
  const auto row = thesis_row(a.sequence);
  return pad(a.sequence + " " + (row ? std::string(row->label) : std::string("-")), 13);
}

void print_table(std::ostream& out, const std::vector<SequenceAnalysis>& results, bool r_squared) {
  const char* pattern = r_squared ? "%.3f" : "%.1f";
  const std::size_t width = r_squared ? 16 : 14;
  out << pad("sequence", 13);
  for (const auto& model : results.front().models) out << pad_left(model.title, width);
  out << "\n";
  for (const auto& a : results) {
    out << label(a);
    for (const auto& model : a.models) {
      const double ours = r_squared ? model.r_squared : 100.0 * model.rmse_fraction;
      const double theirs = published(a.sequence, model.key, r_squared);
      const std::string cell = format(pattern, ours) + " / " +
                               (std::isnan(theirs) ? std::string("-") : format(pattern, theirs));
      out << pad_left(cell, width);
    }
    out << "\n";
  }
}

}  // namespace

void print_coil_fit_report(std::ostream& out, const std::vector<SequenceAnalysis>& results) {
  if (results.empty()) return;
  out << "Thesis Table 2.2: R^2 (2.15) of the measured mean inductance against each model at the "
         "measured lengths\n(each cell: this program / thesis)\n";
  print_table(out, results, true);
  out << "\nThesis Table 2.3: RMSE of the deflection predicted from the measured mean inductance, "
         "% of the deflection range\n(each cell: this program / thesis)\n";
  print_table(out, results, false);
  for (const auto& a : results)
    for (const auto& model : a.models)
      if (!model.not_invertible.empty())
        out << "  " << a.sequence << ", " << model.title << " (nan): " << model.not_invertible
            << "\n";
  out << "\nRosa   = (2.7)-(2.10), Weaver's closed-form B, correct Nagaoka coefficient.\n"
         "Rosa*  = the published analysis' Rosa: its Nagaoka coefficient comes from an AGM loop "
         "that never iterates\n         (K = pi/2); compared with the thesis' Rosa column.\n"
         "Helix  = Neumann's integral over the helix after Weaver (2011), the thesis' ref. "
         "[167].\n"
         "Fitted = (2.14) through the first and last kept step of the calibration sequence.\n";

  out << "\nFitted model (2.14) L = alpha/l + beta\n"
      << pad("sequence", 13) << pad("calibrated on", 15) << pad_left("alpha [uH mm]", 14)
      << pad_left("beta [uH]", 11) << "\n";
  for (const auto& a : results) {
    out << label(a) << pad(a.calibration, 15) << pad_left(format("%.3f", a.fit.alpha() * 1e9), 14)
        << pad_left(format("%.4f", a.fit.beta() * 1e6), 11) << "\n";
  }

  out << "\nThesis ch. 3: sensitivity to deflection, resistance R against inductance L (kept "
         "steps, 10 readings each)\n"
         "  change  = (last - first step mean) / mean;  slope = least-squares slope of the step "
         "means / mean\n"
         "  t       = slope / its standard error from the reading scatter;  x-noise = "
         "single-reading scatter / |slope|\n"
         "  steps   = successive steps moving with (+) / against (-) the trend by more than 2 "
         "standard errors\n";
  out << pad("", 13) << "| " << pad("resistance R", 59) << " | inductance L\n";
  const std::string header = pad_left("mean", 9) + pad_left("change", 9) + pad_left("slope", 10) +
                             pad_left("t", 8) + pad_left("noise", 8) + pad_left("x-noise", 9) +
                             pad_left("steps", 6);
  out << pad("sequence", 13) << "| " << header << " | " << header << "\n";
  const std::string units = pad_left("", 9) + pad_left("[%]", 9) + pad_left("[%/mm]", 10) +
                            pad_left("", 8) + pad_left("[ppm]", 8) + pad_left("[mm]", 9) +
                            pad_left("+/-", 6);
  out << pad("", 13) << "| " << units << " | " << units << "\n";
  const auto row = [](const ImpedanceSensitivity& s, double scale, const char* mean_pattern) {
    return pad_left(format(mean_pattern, s.mean * scale), 9) +
           pad_left(format("%+.3f", 100.0 * s.relative_change), 9) +
           pad_left(format("%+.4f", 100.0 * s.relative_slope * 1e-3), 10) +
           pad_left(format("%+.1f", s.slope_t), 8) +
           pad_left(format("%.0f", 1e6 * s.noise / s.mean), 8) +
           pad_left(format("%.3g", s.deflection_noise * 1e3), 9) +
           pad_left(
               std::to_string(s.significant_steps) + "/" + std::to_string(s.significant_reversals),
               6) +
           " ";
  };
  for (const auto& a : results) {
    out << label(a) << "| " << row(a.resistance, 1.0, "%.5f") << " | "
        << row(a.inductance, 1e6, "%.4f") << "\n";
  }
  out << "  (R mean in ohm, L mean in uH)\n";
}

void write_coil_fit_hdf5(const std::string& path, const std::vector<SequenceAnalysis>& results,
                         const CoilFitProvenance& provenance) {
  Hdf5Writer file(path);
  Provenance files{provenance.command_line, {}};
  for (const auto& spring : provenance.spring_files) {
    std::ifstream in(spring);
    std::ostringstream text;
    text << in.rdbuf();
    files.configs.push_back({spring, text.str(), ""});
  }
  file.provenance(files);
  file.attribute("/", "command", "coil-fit");
  file.attribute("/", "data_directory", provenance.data_directory);
  std::string springs;
  for (const auto& spring : provenance.spring_files)
    springs += (springs.empty() ? "" : "\n") + spring;
  file.attribute("/", "spring_files", springs);
  file.attribute("/", "thesis_tables",
                 "J.O. van der Weijde, Self-sensing of coil springs and twisted and coiled polymer "
                 "muscles, TU Delft 2020, Tables 2.2 and 2.3");

  std::vector<std::string> sequences, models;
  for (const auto& a : results) sequences.push_back(a.sequence);
  for (const auto& m : results.front().models) models.push_back(m.title);
  const std::size_t rows = results.size(), columns = models.size();
  std::vector<double> r2(rows * columns), r2_thesis(rows * columns), rmse(rows * columns),
      rmse_thesis(rows * columns);
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t j = 0; j < columns; ++j) {
      const auto& m = results[i].models[j];
      r2[i * columns + j] = m.r_squared;
      rmse[i * columns + j] = 100.0 * m.rmse_fraction;
      r2_thesis[i * columns + j] = published(results[i].sequence, m.key, true);
      rmse_thesis[i * columns + j] = published(results[i].sequence, m.key, false);
    }
  }
  file.write_strings("/tables/sequences", sequences);
  file.write_strings("/tables/models", models);
  file.write_matrix("/tables/r_squared", r2, rows, columns, "1");
  file.write_matrix("/tables/r_squared_thesis", r2_thesis, rows, columns, "1");
  file.write_matrix("/tables/rmse_percent", rmse, rows, columns, "%");
  file.write_matrix("/tables/rmse_percent_thesis", rmse_thesis, rows, columns, "%");
  file.attribute("/tables", "description",
                 "rows: sequences; columns: models. *_thesis: the published values (Rosa* is "
                 "compared with the published Rosa column; NaN where the thesis has none)");

  std::vector<double> r_slope, r_t, r_change, l_slope, l_t, l_change;
  for (const auto& a : results) {
    const std::string g = "/" + a.sequence;
    file.write_scalar(g + "/geometry/radius", a.radius, "m");
    file.write_scalar(g + "/geometry/wire_diameter", a.wire_diameter, "m");
    file.write_scalar(g + "/geometry/coil_length", a.coil_length, "m");
    file.write_scalar(g + "/geometry/turns", a.turns, "1");
    file.write(g + "/deflection", a.deflection, "m");
    file.write(g + "/length", a.length, "m");
    file.write(g + "/inductance_mean", a.inductance_mean, "H");
    file.write(g + "/inductance_std", a.inductance_std, "H");
    file.write(g + "/resistance_mean", a.resistance.step_mean, "ohm");
    file.write(g + "/resistance_std", a.resistance.step_std, "ohm");
    std::vector<double> l_readings, r_readings;
    for (std::size_t i = 0; i < a.kept.steps(); ++i) {
      l_readings.insert(l_readings.end(), a.kept.inductance[i].begin(), a.kept.inductance[i].end());
      r_readings.insert(r_readings.end(), a.kept.resistance[i].begin(), a.kept.resistance[i].end());
    }
    const std::size_t readings = a.kept.inductance.front().size();
    file.write_matrix(g + "/inductance_readings", l_readings, a.kept.steps(), readings, "H");
    file.write_matrix(g + "/resistance_readings", r_readings, a.kept.steps(), readings, "ohm");
    file.write(g + "/table/length", a.table_length, "m");
    file.write(g + "/table/deflection", a.table_deflection, "m");
    file.write_scalar(g + "/fit/alpha", a.fit.alpha(), "H*m");
    file.write_scalar(g + "/fit/beta", a.fit.beta(), "H");
    file.attribute(g + "/fit", "calibration_sequence", a.calibration);
    for (const auto& m : a.models) {
      const std::string mg = g + "/models/" + m.key;
      file.write(mg + "/inductance", m.inductance, "H");
      file.write(mg + "/table_inductance", m.table_inductance, "H");
      file.write(mg + "/predicted_deflection", m.predicted_deflection, "m");
      if (!m.not_invertible.empty()) file.attribute(mg, "not_invertible", m.not_invertible);
      file.write_scalar(mg + "/r_squared", m.r_squared, "1");
      file.write_scalar(mg + "/rmse_percent", 100.0 * m.rmse_fraction, "%");
    }
    for (const auto& [name, s, unit] : {std::tuple{"resistance", &a.resistance, "ohm"},
                                        std::tuple{"inductance", &a.inductance, "H"}}) {
      const std::string cg = "/chapter3/" + a.sequence + "/" + name;
      file.write(cg + "/step_mean", s->step_mean, unit);
      file.write(cg + "/step_std", s->step_std, unit);
      file.write_scalar(cg + "/mean", s->mean, unit);
      file.write_scalar(cg + "/noise", s->noise, unit);
      file.write_scalar(cg + "/slope", s->slope, std::string(unit) + "/m");
      file.write_scalar(cg + "/slope_standard_error", s->slope_error, std::string(unit) + "/m");
      file.write_scalar(cg + "/slope_t", s->slope_t, "1");
      file.write_scalar(cg + "/line_r_squared", s->line_r_squared, "1");
      file.write_scalar(cg + "/excess_scatter", s->excess_scatter, "1");
      file.write_scalar(cg + "/relative_change", s->relative_change, "1");
      file.write_scalar(cg + "/relative_slope", s->relative_slope, "1/m");
      file.write_scalar(cg + "/deflection_noise", s->deflection_noise, "m");
      file.write_scalar(cg + "/significant_steps", s->significant_steps, "1");
      file.write_scalar(cg + "/significant_reversals", s->significant_reversals, "1");
    }
    r_slope.push_back(a.resistance.relative_slope);
    r_t.push_back(a.resistance.slope_t);
    r_change.push_back(a.resistance.relative_change);
    l_slope.push_back(a.inductance.relative_slope);
    l_t.push_back(a.inductance.slope_t);
    l_change.push_back(a.inductance.relative_change);
  }
  file.write_strings("/chapter3/sequences", sequences);
  file.write("/chapter3/resistance_relative_slope", r_slope, "1/m");
  file.write("/chapter3/resistance_slope_t", r_t, "1");
  file.write("/chapter3/resistance_relative_change", r_change, "1");
  file.write("/chapter3/inductance_relative_slope", l_slope, "1/m");
  file.write("/chapter3/inductance_slope_t", l_t, "1");
  file.write("/chapter3/inductance_relative_change", l_change, "1");
  file.commit();
}

}  // namespace tcpmsim::analysis
