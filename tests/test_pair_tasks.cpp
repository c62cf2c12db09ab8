// The antagonistic pair's joint-angle tasks beside the single muscle's deflection tasks
// (issue 10): calibrated like section 7.3.4, analysed by the control-task functions.
#include <catch2/catch.hpp>

#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "analysis/control_tasks_command.h"
#include "analysis/pair_task_runner.h"
#include "analysis/statistics.h"
#include "sim/memory_record.h"
#include "sim/run.h"
#include "tests/support/test_support.h"

using namespace tcpmsim;
using namespace tcpmsim::testing;

namespace {

// The upper median (the middle value; of an even count, the higher of the two), as the report.
double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Reached rise times of the steps whose target lies above (+1) or below (-1) their start.
std::vector<double> rise_times(const std::vector<StepRise>& rises, int direction) {
  std::vector<double> times;
  for (const auto& rise : rises)
    if (rise.reached && (rise.target - rise.start) * direction > 0) times.push_back(rise.rise_time);
  return times;
}

}  // namespace

TEST_CASE("Each muscle's calibration offset removes its estimator's deflection bias") {
  ControlTaskSettings settings;
  const std::string config = source_path("configs/pair/angle_steps.yaml");
  const auto results = run_pair_tasks({config}, settings, shared_units());
  REQUIRE(results.size() == 1);
  // Without it the self-sensed deflections are off by a millimetre or more (the 1 ns timer).
  CHECK(std::abs(results[0].left_offset) > 0.3e-3);
  CHECK(std::abs(results[0].right_offset) > 0.3e-3);
  // Holding the middle again with the offsets applied, each estimate is right on average.
  Scenario hold = load_scenario(config, {"controller.reference=0 rad", "scenario.duration=40 s"},
                                shared_units());
  Context context = hold.make_context();
  context.set_parameter("left_estimator.calibration.deflection_offset", results[0].left_offset);
  context.set_parameter("right_estimator.calibration.deflection_offset", results[0].right_offset);
  MemoryRecord record(*hold.system);
  integrate(hold, context, record);
  for (const auto& [side, offset] :
       {std::pair{"left", results[0].left_offset}, std::pair{"right", results[0].right_offset}}) {
    INFO(side);
    double error = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < record.time.size(); ++k) {
      if (record.time[k] < 30.0) continue;
      error += record[std::string(side) + "_estimator/deflection"][k] -
               record[std::string("load/") + side + "_deflection"][k];
      ++count;
    }
    // What remains is the loop moving a little once its estimates are corrected.
    CHECK(std::abs(error / count) < 0.1 * std::abs(offset));
  }
  // The task runs with them: the self-sensed angle, ((x_l - x0) - (x_r - x0)) / (2 r), moves
  // against the uncalibrated run by (o_left - o_right) / (2 r), r = 10 mm.
  settings.calibrate = false;
  const auto plain = run_pair_tasks({config}, settings, shared_units());
  const auto mean_error = [](const PairTaskResult& result) {
    return analysis::mean(result.estimation_errors);
  };
  CHECK(mean_error(results[0]) - mean_error(plain[0]) ==
        Approx((results[0].left_offset - results[0].right_offset) / (2 * 10e-3)).epsilon(0.1));
}

TEST_CASE("The pair drives both directions by heating; the single muscle waits for cooling") {
  ControlTaskSettings settings;
  const auto pair =
      run_pair_tasks({source_path("configs/pair/angle_steps.yaml")}, settings, shared_units());
  const auto single = run_control_tasks({source_path("configs/ch7_control/deflection_steps.yaml")},
                                        settings, shared_units());
  // Every step of the pair reaches its target, both ways.
  CHECK(rise_times(pair[0].rises, +1).size() + rise_times(pair[0].rises, -1).size() ==
        pair[0].rises.size());
  // The single muscle under a constant force heats to shorten (deflection down) and cools to
  // lengthen: its cooling steps are the slow ones. The pair's slower direction is still faster.
  const double single_cooling = median(rise_times(single[0].rises, +1));
  const double single_heating = median(rise_times(single[0].rises, -1));
  CHECK(single_cooling > 2.0 * single_heating);
  CHECK(std::max(median(rise_times(pair[0].rises, +1)), median(rise_times(pair[0].rises, -1))) <
        single_cooling);
}

TEST_CASE("control-tasks reports a pair beside the single muscle") {
  ControlTasksOptions options;
  options.configs = {source_path("configs/ch7_control/deflection_steps.yaml"),
                     source_path("configs/pair/angle_steps.yaml")};
  options.output = (std::filesystem::temp_directory_path() / "tcpmsim_pair_tasks.h5").string();
  std::ostringstream out;
  run_control_tasks_command(options, out, shared_units());
  CHECK_THAT(out.str(),
             Catch::Contains("Antagonistic pair (joint angle) beside the single muscle"));
  CHECK_THAT(out.str(), Catch::Contains("pair_angle_steps: calibration offsets"));
  // The pair's analysis is in the report file beside the single muscle's.
  H5::H5File file(options.output, H5F_ACC_RDONLY);
  CHECK(file.nameExists("pair_angle_steps/calibration_offsets"));
  CHECK(file.nameExists("pair_angle_steps/rise_time"));
  CHECK(file.nameExists("ch7_deflection_steps/rise_time"));
  file.close();
  std::filesystem::remove(options.output);
}

TEST_CASE("A pair config without steps or a sweep is no control task, and says so first") {
  ControlTasksOptions options;
  options.configs = {source_path("configs/ch7_control/deflection_steps.yaml"),
                     source_path("configs/pair/pretension_change.yaml")};
  options.output = (std::filesystem::temp_directory_path() / "tcpmsim_not_a_task.h5").string();
  std::ostringstream out;
  CHECK_THROWS_WITH(run_control_tasks_command(options, out, shared_units()),
                    Catch::Contains("controller.reference: a control task's reference is a step "
                                    "sequence"));
  CHECK(!std::filesystem::exists(options.output));
}
