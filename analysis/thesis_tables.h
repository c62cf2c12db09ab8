#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace tcpmsim::analysis {

// Published values of thesis Tables 2.2 and 2.3 (J.O. van der Weijde, "Self-sensing of coil
// springs and twisted and coiled polymer muscles", TU Delft 2020, ch. 2; also IROS 2015),
// columns Basic, Nagaoka, Rosa, Maxwell, Neumann (Helix), Fitted.
enum ThesisColumn : int { kBasic, kNagaoka, kRosa, kMaxwell, kHelix, kFitted, kThesisColumns };

struct ThesisRow {
  std::string_view sequence;                        // data file stem
  std::string_view label;                           // the thesis' row label
  std::array<double, kThesisColumns> r_squared;     // Table 2.2
  std::array<double, kThesisColumns> rmse_percent;  // Table 2.3, % of the deflection range
};

// The row for a sequence (S1_01 ... S4_01), if the thesis lists it.
std::optional<ThesisRow> thesis_row(std::string_view sequence);

}  // namespace tcpmsim::analysis
