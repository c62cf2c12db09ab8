#pragma once

#include <memory>
#include <string>
#include <vector>

#include "models/coil_spring_chain.h"
#include "models/inductance/maxwell_evaluator.h"
#include "sim/component.h"
#include "sim/config/config_node.h"
#include "sim/parameter_bindings.h"

namespace tcpmsim {

// Inductance-based force sensing on a vibrating coil spring (thesis section 4.2.2, 4.3.3).
// Reads the winding positions of a CoilSpringChain and observes
//   L    by Maxwell's summation over the actual gaps (4.8)-(4.11),
//   x^   from the fit 1/(l0 + x) = alpha L + beta (4.13),
//   F_L  = k x^.
// The fit is made on uniform winding distributions across the operating range by least squares,
// constrained to pass exactly through the static preload (4.13); so F_L equals F_x at rest, and
// any difference comes from non-uniform windings.
// The self term uses the round wire's geometric mean distance (delta/2) e^(-1/4), as in the
// text under (2.11); the printed (4.10) has delta/4. The fit absorbs the choice (it shifts L by
// a constant N M(g)), which the tests confirm.
struct CoilSpringInductanceParameters {
  int windings = 0;
  double coil_radius = 0.0;      // r [m]
  double wire_diameter = 0.0;    // delta [m]
  double rest_length = 0.0;      // l0 [m]
  double stiffness = 0.0;        // k [N/m]
  double shortest_length = 0.0;  // l_min of the operating range [m]
  double longest_length = 0.0;   // l_max [m]
  double preload_length = 0.0;   // the static length the fit must reproduce [m]
};

// Whether the geometry can be a coil, and if not, the key to blame and why:
// the wire must fit inside the coil radius, and the N windings must not overlap anywhere in the
// operating range (l_min > N delta, the solid length), which also keeps every ring distance
// inside the range Maxwell's evaluator tabulates.
struct CoilGeometryProblem {
  std::string key;      // "" when the geometry is a coil
  std::string problem;  // why it is not
  std::string message() const { return key + ": " + problem; }
};
CoilGeometryProblem coil_geometry_problem(const CoilSpringInductanceParameters& parameters);

// The constrained least-squares fit of (4.13): y = 1/l = alpha L + beta through (L_p, y_p).
struct InverseLengthFit {
  double alpha = 0.0;  // [1/(H m)]
  double beta = 0.0;   // [1/m]
  double length(double inductance) const { return 1.0 / (alpha * inductance + beta); }
};

// The sensor's model for one set of parameters: Maxwell's evaluator and the fit on it.
class SpringInductanceModel {
 public:
  explicit SpringInductanceModel(const CoilSpringInductanceParameters& parameters);
  // L of a spring of length l with uniform windings (the fit's data).
  double uniform_inductance(double length) const;
  const InverseLengthFit& fit() const { return fit_; }
  const CoilSpringInductanceParameters& parameters() const { return parameters_; }
  const inductance::MaxwellEvaluator& evaluator() const { return evaluator_; }

 private:
  InverseLengthFit fit_operating_range() const;
  CoilSpringInductanceParameters parameters_;
  inductance::MaxwellEvaluator evaluator_;
  InverseLengthFit fit_;
};

class CoilSpringInductance final : public Component {
 public:
  enum Output { kInductance, kEstimatedDeflection, kEstimatedForce };
  // The spring's rest length and stiffness are the chain's parameters, read by path
  // (`rest_length_path`, `stiffness_path`) when a run starts.
  CoilSpringInductance(std::string group, CoilSpringInductanceParameters defaults,
                       ParameterBindings<CoilSpringInductanceParameters> bindings,
                       std::string rest_length_path, std::string stiffness_path);
  // Keys coil_radius, wire_diameter, operating_range, preload_length (default
  // `initial_length`, the static length between the chain's ends at the start).
  static std::unique_ptr<CoilSpringInductance> from_config(const std::string& group,
                                                           const ConfigNode& node,
                                                           const CoilSpringParameters& chain,
                                                           double initial_length,
                                                           const std::string& chain_group);

  std::vector<OutputDeclaration> outputs() const override;
  std::vector<InputDeclaration> inputs() const override;
  std::vector<ParameterDeclaration> parameters() const override;
  std::string check_parameters(const RunSetup& setup) const override;
  std::unique_ptr<RunState> create_run_state(const RunSetup& setup) const override;
  void compute_observations(const Evaluation& evaluation) const override;

  // The model as built.
  const CoilSpringInductanceParameters& defaults() const { return built_->parameters(); }

 private:
  struct Run;
  CoilSpringInductanceParameters run_parameters(const RunSetup& setup) const;
  std::shared_ptr<const SpringInductanceModel> built_;
  ParameterBindings<CoilSpringInductanceParameters> bindings_;
  std::string rest_length_path_;
  std::string stiffness_path_;
};

}  // namespace tcpmsim
