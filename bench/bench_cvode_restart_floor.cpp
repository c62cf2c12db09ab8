// The floor under any CVODE-based closed loop on this machine's SUNDIALS build: the averaged
// closed-loop task's two plant states, (7.1) and the SLS in force mode (7.5)-(7.6), written as
// a bare CVODE program with a three-line right-hand side, no components, no outputs, and the
// same restart at every 20 Hz sample with a new power held over the sample. The power comes
// from a saturated proportional law on the deflection, so the solution wanders over the same
// operating range as under the PID. Same rtol (1e-5) and absolute tolerances as tcpmsim's
// states. Prints the median wall time and CVODE's counts, for the benchmark script to set
// against tcpmsim's own run of the same task. No assertions.
#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {
// Table 7.2 (SI) and the deflection task's load and limits.
constexpr double kHeatingGain = 7.2e-3, kCoolingRate = 131.6e-3;                  // N/J, 1/s
constexpr double kK1 = 10.8, kK2 = 2.7, kDamping = 4.3, kForceOffset = 106.9e-3;  // SI
constexpr double kLoadForce = 0.40, kMinPower = 0.10, kMaxPower = 3.12;           // N, W
constexpr double kPeriod = 0.05;                                                  // 20 Hz

struct Plant {
  double power = 0.0;
  double deflection(const double* y) const {  // (7.5) solved for x at the imposed force
    return (kLoadForce - y[0] - kForceOffset + kK2 * y[1]) / (kK1 + kK2);
  }
};

int right_hand_side(double, N_Vector state, N_Vector derivative, void* user) {
  const auto& plant = *static_cast<const Plant*>(user);
  const double* y = N_VGetArrayPointer(state);
  double* dy = N_VGetArrayPointer(derivative);
  dy[0] = kHeatingGain * plant.power - kCoolingRate * y[0];  // (7.1)
  dy[1] = kK2 / kDamping * (plant.deflection(y) - y[1]);     // the dashpot of (7.6)
  return 0;
}

struct Counts {
  long steps = 0, rhs = 0, jacobians = 0;
};

double run(bool adams, double duration, Counts& counts) {
  SUNContext context = nullptr;
  SUNContext_Create(nullptr, &context);
  Plant plant;
  N_Vector state = N_VNew_Serial(2, context);
  N_Vector tolerances = N_VNew_Serial(2, context);
  double* y = N_VGetArrayPointer(state);
  y[0] = 0.0;
  y[1] = (kLoadForce - kForceOffset) / kK1;   // rested at 0.40 N
  N_VGetArrayPointer(tolerances)[0] = 1e-10;  // N, as ReducedThermalForce
  N_VGetArrayPointer(tolerances)[1] = 1e-12;  // m, as SlsMechanics
  void* memory = CVodeCreate(adams ? CV_ADAMS : CV_BDF, context);
  CVodeInit(memory, right_hand_side, 0.0, state);
  CVodeSetUserData(memory, &plant);
  CVodeSVtolerances(memory, 1e-5, tolerances);
  CVodeSetMaxNumSteps(memory, -1);
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  SUNNonlinearSolver fixed_point = nullptr;
  if (adams) {
    fixed_point = SUNNonlinSol_FixedPoint(state, 0, context);
    CVodeSetNonlinearSolver(memory, fixed_point);
  } else {
    matrix = SUNDenseMatrix(2, 2, context);
    linear_solver = SUNLinSol_Dense(state, matrix, context);
    CVodeSetLinearSolver(memory, linear_solver, matrix);
  }
  const auto started = std::chrono::steady_clock::now();
  const long samples = static_cast<long>(duration / kPeriod + 0.5);
  double t = 0.0;
  for (long k = 1; k <= samples; ++k) {
    const double reference = 0.020 + 0.005 * ((k / 400) % 2 == 0 ? 1.0 : -1.0);  // 20 s steps
    plant.power =
        std::clamp(1.41 - 1080.0 * (reference - plant.deflection(y)), kMinPower, kMaxPower);
    if (k > 1) CVodeReInit(memory, t, state);
    const double stop = static_cast<double>(k) * kPeriod;
    CVodeSetStopTime(memory, stop);
    double reached = t;
    while (reached < stop) {
      if (CVode(memory, stop, state, &reached, CV_ONE_STEP) == CV_TSTOP_RETURN) reached = stop;
    }
    long steps = 0, rhs = 0, jacobians = 0;
    CVodeGetNumSteps(memory, &steps);
    CVodeGetNumRhsEvals(memory, &rhs);
    if (!adams) CVodeGetNumJacEvals(memory, &jacobians);
    counts.steps += steps, counts.rhs += rhs, counts.jacobians += jacobians;
    t = stop;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  CVodeFree(&memory);
  if (linear_solver) SUNLinSolFree(linear_solver);
  if (matrix) SUNMatDestroy(matrix);
  if (fixed_point) SUNNonlinSolFree(fixed_point);
  N_VDestroy(tolerances);
  N_VDestroy(state);
  SUNContext_Free(&context);
  return seconds;
}
}  // namespace

int main(int argc, char** argv) {
  const bool adams = argc > 1 && std::strcmp(argv[1], "adams") == 0;
  const double duration = argc > 2 ? std::atof(argv[2]) : 1000.0;
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 5;
  std::vector<double> seconds;
  Counts counts;
  for (int k = 0; k < repeats; ++k) {
    counts = {};
    seconds.push_back(run(adams, duration, counts));
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("median_seconds=%.6g min_seconds=%.6g steps=%ld rhs=%ld jacobians=%ld segments=%ld\n",
              seconds[seconds.size() / 2], seconds.front(), counts.steps, counts.rhs,
              counts.jacobians, static_cast<long>(duration / kPeriod + 0.5));
  return 0;
}
