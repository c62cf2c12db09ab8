#include "models/coil_spring_inductance.h"

#include <cstdio>
#include <tuple>

#include "models/inductance/loop_mutual.h"
#include "models/typical_values.h"
#include "sim/context.h"
#include "sim/value_check.h"

namespace tcpmsim {

namespace {
constexpr int kFitLengths = 25;

bool same(const CoilSpringInductanceParameters& a, const CoilSpringInductanceParameters& b) {
  return std::tie(a.windings, a.coil_radius, a.wire_diameter, a.rest_length, a.stiffness,
                  a.shortest_length, a.longest_length, a.preload_length) ==
         std::tie(b.windings, b.coil_radius, b.wire_diameter, b.rest_length, b.stiffness,
                  b.shortest_length, b.longest_length, b.preload_length);
}
}  // namespace

CoilGeometryProblem coil_geometry_problem(const CoilSpringInductanceParameters& p) {
  if (!(p.coil_radius > 0.5 * p.wire_diameter)) {
    return {"coil_radius", number_text(p.coil_radius) +
                               " m is not larger than half the wire "
                               "diameter (" +
                               number_text(0.5 * p.wire_diameter) +
                               " m): the wire does not fit in the coil"};
  }
  const double solid_length = p.windings * p.wire_diameter;
  if (!(p.shortest_length > solid_length)) {
    return {"operating_range",
            "the shortest length " + number_text(p.shortest_length) +
                " m is not longer than the solid length, windings x wire_diameter = " +
                std::to_string(p.windings) + " x " + number_text(p.wire_diameter) +
                " m = " + number_text(solid_length) + " m: the windings would overlap"};
  }
  return {};
}

SpringInductanceModel::SpringInductanceModel(const CoilSpringInductanceParameters& parameters)
    : parameters_(parameters),
      evaluator_(parameters.coil_radius, inductance::wire_gmd(parameters.wire_diameter),
                 0.05 * parameters.wire_diameter, 2.0 * parameters.longest_length),
      fit_(fit_operating_range()) {}

double SpringInductanceModel::uniform_inductance(double length) const {
  // Rings at (i + 1/2) l / N: pitch l / N, all N rings (4.11) with uniform gaps (2.13).
  return evaluator_.inductance_uniform(parameters_.windings, length / parameters_.windings);
}

InverseLengthFit SpringInductanceModel::fit_operating_range() const {
  // Minimise sum (y_k - alpha L_k - beta)^2 with y = 1/l, subject to y_p = alpha L_p + beta:
  // beta = y_p - alpha L_p and alpha = sum dL dy / sum dL^2 about the preload point.
  const double preload_inductance = uniform_inductance(parameters_.preload_length);
  const double preload_inverse = 1.0 / parameters_.preload_length;
  double covariance = 0.0, variance = 0.0;
  for (int k = 0; k < kFitLengths; ++k) {
    const double length =
        parameters_.shortest_length +
        (parameters_.longest_length - parameters_.shortest_length) * k / (kFitLengths - 1);
    const double dL = uniform_inductance(length) - preload_inductance;
    covariance += dL * (1.0 / length - preload_inverse);
    variance += dL * dL;
  }
  InverseLengthFit fit;
  fit.alpha = covariance / variance;
  fit.beta = preload_inverse - fit.alpha * preload_inductance;
  return fit;
}

// The model of this run (shared with the built one when the parameters are the same) and the
// scratch for the winding positions.
struct CoilSpringInductance::Run final : RunState {
  std::shared_ptr<const SpringInductanceModel> model;
  std::vector<double> positions;
};

CoilSpringInductance::CoilSpringInductance(
    std::string group, CoilSpringInductanceParameters defaults,
    ParameterBindings<CoilSpringInductanceParameters> bindings, std::string rest_length_path,
    std::string stiffness_path)
    : Component(std::move(group), "coil_spring_inductance"),
      built_(std::make_shared<const SpringInductanceModel>(defaults)),
      bindings_(std::move(bindings)),
      rest_length_path_(std::move(rest_length_path)),
      stiffness_path_(std::move(stiffness_path)) {}

std::unique_ptr<CoilSpringInductance> CoilSpringInductance::from_config(
    const std::string& group, const ConfigNode& node, const CoilSpringParameters& chain,
    double initial_length, const std::string& chain_group) {
  node.declare({"coil_radius", "wire_diameter", "operating_range", "preload_length"});
  CoilSpringInductanceParameters p;
  ParameterBindings<CoilSpringInductanceParameters> bind;
  p.windings = chain.windings;
  p.rest_length = chain.rest_length;
  p.stiffness = chain.stiffness;
  bind.quantity(node, "coil_radius", "m", typical::coil_radius(ValueCheck::positive()), p,
                bind.member(&CoilSpringInductanceParameters::coil_radius));
  bind.quantity(node, "wire_diameter", "m", typical::wire_diameter(ValueCheck::positive()), p,
                bind.member(&CoilSpringInductanceParameters::wire_diameter));
  bind.interval(node, "operating_range", "m", ValueCheck::positive(), p,
                bind.member(&CoilSpringInductanceParameters::shortest_length),
                bind.member(&CoilSpringInductanceParameters::longest_length));
  bind.quantity_or(node, "preload_length", "m", initial_length, ValueCheck::positive(), p,
                   bind.member(&CoilSpringInductanceParameters::preload_length));
  if (const CoilGeometryProblem found = coil_geometry_problem(p); !found.key.empty())
    node.at(found.key).fail(found.problem);
  return std::make_unique<CoilSpringInductance>(
      group, p, std::move(bind), chain_group + ".rest_length", chain_group + ".stiffness");
}

std::vector<OutputDeclaration> CoilSpringInductance::outputs() const {
  return {{"inductance", "H", true},
          {"inductance_deflection", "m", true},
          {"inductance_force", "N", true}};
}

std::vector<InputDeclaration> CoilSpringInductance::inputs() const {
  std::vector<InputDeclaration> declared;
  char name[32];
  for (int i = 0; i < defaults().windings; ++i) {
    std::snprintf(name, sizeof name, "winding_%02d", i + 1);
    declared.push_back({name, true});
  }
  return declared;
}

std::vector<ParameterDeclaration> CoilSpringInductance::parameters() const {
  return bindings_.declarations(defaults());
}

CoilSpringInductanceParameters CoilSpringInductance::run_parameters(const RunSetup& setup) const {
  CoilSpringInductanceParameters p = bindings_.assign(defaults(), setup.parameters);
  p.rest_length = setup.context.parameter(rest_length_path_);
  p.stiffness = setup.context.parameter(stiffness_path_);
  return p;
}

std::string CoilSpringInductance::check_parameters(const RunSetup& setup) const {
  const CoilGeometryProblem found = coil_geometry_problem(run_parameters(setup));
  return found.key.empty() ? std::string() : found.message();
}

std::unique_ptr<RunState> CoilSpringInductance::create_run_state(const RunSetup& setup) const {
  const CoilSpringInductanceParameters p = run_parameters(setup);
  auto run = std::make_unique<Run>();
  run->model = same(p, defaults()) ? built_ : std::make_shared<const SpringInductanceModel>(p);
  run->positions.assign(static_cast<std::size_t>(p.windings), 0.0);
  return run;
}

void CoilSpringInductance::compute_observations(const Evaluation& evaluation) const {
  Run& run = mutable_run_state<Run>(evaluation);
  const SpringInductanceModel& model = *run.model;
  for (int i = 0; i < model.parameters().windings; ++i)
    run.positions[static_cast<std::size_t>(i)] = input(evaluation, i);
  const double inductance = model.evaluator().inductance(run.positions);  // (4.11)
  const double deflection =
      model.fit().length(inductance) - model.parameters().rest_length;  // (4.13)
  set_output(evaluation, kInductance, inductance);
  set_output(evaluation, kEstimatedDeflection, deflection);
  set_output(evaluation, kEstimatedForce, model.parameters().stiffness * deflection);  // F_L
}

}  // namespace tcpmsim
