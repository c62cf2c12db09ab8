#include "analysis/thesis_tables.h"

namespace tcpmsim::analysis {

namespace {

// Thesis Table 2.2 (R^2) and Table 2.3 (RMSE of the predicted deflection, % of its range),
// transcribed from the thesis text; S1-a ... S1-e are the sequences S1_01 ... S1_05.
// clang-format off
constexpr std::array<ThesisRow, 8> kRows{{
    // sequence  label   R^2: Basic Nagaoka Rosa Maxwell Helix Fitted;  RMSE [%]: same order
    {"S1_01", "S1-a", { 0.829, 0.997,  0.216,  0.294, 0.793, 0.998}, {12.6,  1.4, 30.2, 28.4, 14.7, 1.3}},
    {"S1_02", "S1-b", { 0.846, 0.995,  0.181,  0.260, 0.775, 0.999}, {11.9,  2.0, 30.9, 29.1, 15.4, 0.8}},
    {"S1_03", "S1-c", { 0.839, 0.996,  0.211,  0.289, 0.787, 0.999}, {12.4,  1.6, 30.4, 28.6, 14.9, 1.1}},
    {"S1_04", "S1-d", { 0.814, 0.998,  0.250,  0.326, 0.809, 0.997}, {13.2,  1.0, 29.5, 27.7, 14.0, 1.9}},
    {"S1_05", "S1-e", { 0.830, 0.997,  0.206,  0.285, 0.790, 0.998}, {12.5,  1.5, 30.3, 28.5, 14.8, 1.2}},
    {"S2_01", "S2",   { 0.953, 0.653, -0.414, -0.097, 0.182, 0.999}, { 5.8, 19.2, 41.4, 35.3, 30.4, 0.9}},
    {"S3_01", "S3",   { 0.997, 0.838,  0.195,  0.217, 0.539, 0.996}, { 1.9, 12.9, 31.4, 30.8, 23.1, 1.9}},
    {"S4_01", "S4",   {-4.143, 0.790,  0.622,  0.940, 0.998, 1.000}, {54.2, 12.6, 20.5,  8.1,  1.3, 0.3}},
}};
// clang-format on

}  // namespace

std::optional<ThesisRow> thesis_row(std::string_view sequence) {
  for (const auto& row : kRows) {
    if (row.sequence == sequence) return row;
  }
  return std::nullopt;
}

}  // namespace tcpmsim::analysis
