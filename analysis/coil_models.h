#pragma once

#include <array>
#include <string_view>

#include "models/inductance/coil_geometry.h"

namespace tcpmsim::analysis {

// The theoretical columns of thesis Tables 2.2 and 2.3, plus the published Rosa reproduction.
enum class CoilModel { basic, nagaoka, rosa, rosa_published, maxwell, helix };

inline constexpr std::array<CoilModel, 6> kCoilModels{CoilModel::basic,   CoilModel::nagaoka,
                                                      CoilModel::rosa,    CoilModel::rosa_published,
                                                      CoilModel::maxwell, CoilModel::helix};

std::string_view model_key(CoilModel model);    // "maxwell": HDF5 group names
std::string_view model_title(CoilModel model);  // "Maxwell": table headings

// Inductance [H] of the spring's coil at the geometry's length:
//   basic (2.2), nagaoka (2.3)-(2.6), rosa (2.7)-(2.10) with Weaver's closed-form B (as the
//   published analysis), rosa_published (published_rosa.h), maxwell (2.11)-(2.13) with round(N)
//   rings for the mutual terms and N for the self term, helix (2.1) after Weaver with relative
//   tolerance 1e-9.
double model_inductance(CoilModel model, const inductance::CoilGeometry& coil);

}  // namespace tcpmsim::analysis
