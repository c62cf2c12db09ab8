#include "analysis/coil_fit_analysis.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "analysis/statistics.h"
#include "sim/io/delimited_file.h"
#include "sim/value_check.h"

namespace tcpmsim::analysis {

namespace {

std::vector<double> step_means(const std::vector<std::vector<double>>& readings) {
  std::vector<double> means;
  for (const auto& step : readings) means.push_back(mean(step));
  return means;
}

// Why a model's inductance table has no inverse, or "" when it rises or falls all the way.
std::string inversion_problem(const ModelOutcome& outcome, const SequenceAnalysis& a) {
  const auto& table = outcome.table_inductance;
  const bool rising = table.back() > table.front();
  for (std::size_t i = 1; i < table.size(); ++i) {
    if (rising ? table[i] > table[i - 1] : table[i] < table[i - 1]) continue;
    const std::string where = number_text(a.table_length[i - 1] * 1e3) + " mm";
    return "its inductance " +
           (table[i] == table[i - 1] ? "does not change with the coil length near " + where
                                     : "turns near " + where) +
           ", between " + number_text(a.table_length.front() * 1e3) + " and " +
           number_text(a.table_length.back() * 1e3) + " mm: this geometry (" +
           number_text(a.turns) +
           " turns) lies outside the model, and no deflection is read "
           "from it";
  }
  return "";
}

ModelOutcome score(ModelOutcome outcome, const SequenceAnalysis& analysis) {
  outcome.r_squared = r_squared(analysis.inductance_mean, outcome.inductance);
  outcome.rmse_fraction =
      rmse(analysis.deflection, outcome.predicted_deflection) / value_range(analysis.deflection);
  return outcome;
}

}  // namespace

inductance::SpringInductanceFit calibrate(const CoilSpring& spring, const CoilSequence& kept) {
  const double lc = spring.coil_length();
  const auto first = mean(kept.inductance.front());
  const auto last = mean(kept.inductance.back());
  return inductance::SpringInductanceFit::two_point(lc + kept.position.front(), first,
                                                    lc + kept.position.back(), last);
}

SequenceAnalysis analyse_sequence(const CoilSpring& spring, const CoilSequence& kept,
                                  const inductance::SpringInductanceFit& fit,
                                  const std::string& calibration) {
  SequenceAnalysis a;
  a.spring = spring.name;
  a.sequence = kept.name;
  a.calibration = calibration;
  a.wire_diameter = spring.wire_diameter;
  a.radius = spring.radius();
  a.coil_length = spring.coil_length();
  a.turns = spring.turns;
  a.kept = kept;
  a.fit = fit;
  a.deflection = kept.position;
  for (double x : a.deflection) a.length.push_back(a.coil_length + x);
  a.inductance_mean = step_means(kept.inductance);
  for (const auto& step : kept.inductance) a.inductance_std.push_back(standard_deviation(step));
  for (std::size_t i = 0; i < kTablePoints; ++i) {
    const double factor = 1.0 + (kTableStretch - 1.0) * static_cast<double>(i) /
                                    static_cast<double>(kTablePoints - 1);
    a.table_length.push_back(a.coil_length * factor);
    a.table_deflection.push_back(a.table_length.back() - a.coil_length);
  }

  for (const CoilModel model : kCoilModels) {
    ModelOutcome outcome;
    outcome.key = model_key(model);
    outcome.title = model_title(model);
    for (double l : a.length)
      outcome.inductance.push_back(model_inductance(model, spring.at_length(l)));
    for (double l : a.table_length) {
      outcome.table_inductance.push_back(model_inductance(model, spring.at_length(l)));
    }
    // The table inverted by linear inter/extrapolation (MATLAB interp1 'linear', 'extrap').
    outcome.not_invertible = inversion_problem(outcome, a);
    for (double measured : a.inductance_mean) {
      outcome.predicted_deflection.push_back(
          outcome.not_invertible.empty()
              ? interpolate_linear(outcome.table_inductance, a.table_deflection, measured)
              : std::nan(""));
    }
    a.models.push_back(score(std::move(outcome), a));
  }

  ModelOutcome fitted;
  fitted.key = "fitted";
  fitted.title = "Fitted";
  for (double l : a.length) fitted.inductance.push_back(fit.inductance(l));  // (2.14)
  for (double l : a.table_length) fitted.table_inductance.push_back(fit.inductance(l));
  for (double measured : a.inductance_mean) {
    fitted.predicted_deflection.push_back(fit.length(measured) - a.coil_length);  // inverse
  }
  a.models.push_back(score(std::move(fitted), a));

  a.resistance = impedance_sensitivity(a.deflection, kept.resistance);
  a.inductance = impedance_sensitivity(a.deflection, kept.inductance);
  return a;
}

namespace {

// Every step's coil length Lc + x must be positive: a position past -Lc is no coil.
void check_coil_lengths(const CoilSpring& spring, const CoilSequence& sequence) {
  const double coil_length = spring.coil_length();
  for (std::size_t i = 0; i < sequence.steps(); ++i) {
    const double length = coil_length + sequence.position[i];
    if (length > 0.0) continue;
    throw DataFileError(
        {sequence.file, sequence.line[i], sequence.position_column[i], {}},
        "field 4 (measured position [mm]): the coil would be " + number_text(length * 1e3) +
            " mm long (Lc = body_length - "
            "wire_diameter = " +
            number_text(coil_length * 1e3) + " mm of spring " + spring.name + ", plus " +
            number_text(sequence.position[i] * 1e3) + " mm); expected a position above " +
            number_text(-coil_length * 1e3) + " mm");
  }
}

}  // namespace

std::vector<SequenceAnalysis> analyse_coil_springs(const std::vector<CoilSpring>& springs,
                                                   const std::string& data_directory) {
  std::vector<SequenceAnalysis> results;
  for (const CoilSpring& spring : springs) {
    std::vector<CoilSequence> kept;
    for (const auto& entry : spring.sequences) {
      const std::filesystem::path file =
          std::filesystem::path(data_directory.empty() ? spring.data_directory : data_directory) /
          (entry.name + ".csv");
      if (!std::filesystem::is_regular_file(file)) {
        throw ConfigError(entry.location, "coil_spring.sequences",
                          "no data file '" + file.string() + "' for sequence '" + entry.name + "'");
      }
      const CoilSequence sequence = read_coil_sequence(file.string(), entry.name);
      if (sequence.steps() < 3) {
        throw DataFileError(
            {file.string(), sequence.line.empty() ? 1 : sequence.line.back() + 1, 1, {}},
            "expected the free-length line and at least two deflection steps, "
            "got " +
                std::to_string(sequence.steps()) + " lines");
      }
      check_coil_lengths(spring, sequence);
      kept.push_back(sequence.without_first(1));  // the free length: windings touch
    }
    const auto calibration = std::find_if(kept.begin(), kept.end(), [&](const CoilSequence& s) {
      return s.name == spring.calibration;
    });
    const auto fit = calibrate(spring, *calibration);
    for (const CoilSequence& sequence : kept) {
      results.push_back(analyse_sequence(spring, sequence, fit, spring.calibration));
    }
  }
  return results;
}

}  // namespace tcpmsim::analysis
