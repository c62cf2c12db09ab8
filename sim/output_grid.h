#pragma once

// The times a run records: start + k * interval up to the end, then the end itself if that is
// off the grid. One count for the integrator's output and for the record size checked before a
// run starts.
namespace tcpmsim {

// The number of recorded samples in [start, end] (end > start, interval > 0); a double, so that
// the size of a record too large to run can still be stated.
double output_sample_count(double start, double end, double interval);

}  // namespace tcpmsim
