#include "analysis/coil_models.h"

#include "analysis/published_rosa.h"
#include "models/inductance/maxwell.h"
#include "models/inductance/neumann_helix.h"
#include "models/inductance/rosa.h"
#include "models/inductance/solenoid.h"

namespace tcpmsim::analysis {

namespace {
constexpr double kHelixTolerance = 1e-9;
}

std::string_view model_key(CoilModel model) {
  switch (model) {
    case CoilModel::basic:
      return "basic";
    case CoilModel::nagaoka:
      return "nagaoka";
    case CoilModel::rosa:
      return "rosa";
    case CoilModel::rosa_published:
      return "rosa_published";
    case CoilModel::maxwell:
      return "maxwell";
    case CoilModel::helix:
      return "neumann_helix";
  }
  return "";
}

std::string_view model_title(CoilModel model) {
  switch (model) {
    case CoilModel::basic:
      return "Basic";
    case CoilModel::nagaoka:
      return "Nagaoka";
    case CoilModel::rosa:
      return "Rosa";
    case CoilModel::rosa_published:
      return "Rosa*";
    case CoilModel::maxwell:
      return "Maxwell";
    case CoilModel::helix:
      return "Helix";
  }
  return "";
}

double model_inductance(CoilModel model, const inductance::CoilGeometry& coil) {
  using namespace inductance;
  switch (model) {
    case CoilModel::basic:
      return basic_solenoid_inductance(coil);
    case CoilModel::nagaoka:
      return nagaoka_inductance(coil);
    case CoilModel::rosa:
      return rosa_inductance(coil, RosaMutualCorrection::weaver);
    case CoilModel::rosa_published:
      return published_rosa_inductance(coil);
    case CoilModel::maxwell:
      return maxwell_inductance(coil);
    case CoilModel::helix:
      return neumann_helix_inductance(coil, kHelixTolerance);
  }
  return 0.0;
}

}  // namespace tcpmsim::analysis
