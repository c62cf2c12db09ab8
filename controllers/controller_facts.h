#pragma once

#include <string>

#include "sim/config/config_node.h"
#include "sim/scenario_builder.h"

namespace tcpmsim {

inline constexpr const char* kDriveCategory = "drive";
inline constexpr const char* kEstimatorCategory = "estimator";
inline constexpr const char* kControllerCategory = "controller";

// What a Muscle Drive tells the estimator and controller built after it.
struct MuscleDriveFacts {
  double period;       // of the PWM and of every sample taken with it [s]
  bool takes_command;  // no power signal: a controller's command drives it
  ConfigNode section;
  std::string muscle;  // the muscle it heats
};

// What an estimator tells the controller built after it.
struct EstimatorFacts {
  std::string drive;
};

// A sampled component's period follows its drive's PWM frequency in every run.
void follow_pwm(ScenarioBuilder& build, const std::string& sampled, const std::string& drive);

// The Muscle Drive self-sensing reads, or a located error.
const MuscleDriveFacts& sensing_drive(const ConfigNode& node, const std::string& drive,
                                      const ScenarioBuilder& build);

// The drive a controller commands must take commands (no power signal of its own).
void check_takes_command(const MuscleDriveFacts& facts);

}  // namespace tcpmsim
