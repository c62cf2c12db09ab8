// The right-hand side must not allocate: it runs thousands of times per simulated second.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdlib>
#include <new>

#include "tests/support/test_support.h"

namespace {
std::atomic<long> allocations{0};
}

// Counting replacements of every global allocation function (this executable only). All
// variants are replaced so that new and delete always pair up (AddressSanitizer checks).
namespace {
void* counted(std::size_t size) {
  ++allocations;
  return std::malloc(size == 0 ? 1 : size);
}
}  // namespace

void* operator new(std::size_t size) {
  if (void* memory = counted(size)) return memory;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* memory = counted(size)) return memory;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return counted(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return counted(size);
}
void operator delete(void* memory) noexcept {
  std::free(memory);
}
void operator delete[](void* memory) noexcept {
  std::free(memory);
}
void operator delete(void* memory, std::size_t) noexcept {
  std::free(memory);
}
void operator delete[](void* memory, std::size_t) noexcept {
  std::free(memory);
}
void operator delete(void* memory, const std::nothrow_t&) noexcept {
  std::free(memory);
}
void operator delete[](void* memory, const std::nothrow_t&) noexcept {
  std::free(memory);
}

using namespace tcpmsim;
using namespace tcpmsim::testing;

TEST_CASE("A closed loop's sample instants, events and tolerance adaptation allocate nothing") {
  for (const char* config :
       {"configs/ch7_control/force_steps.yaml", "configs/ch7_control/deflection_sweep.yaml"}) {
    for (const char* fidelity : {"drive.fidelity=averaged", "drive.fidelity=switched"}) {
      Scenario scenario = load_scenario(source_path(config), {fidelity}, shared_units());
      const System& system = *scenario.system;
      Context context = scenario.make_context();
      std::vector<double>& state = context.state();
      std::vector<double> absolute(state.size(), 1e-6), relative(state.size(), 1e-6);
      std::vector<double> events(static_cast<std::size_t>(std::max(1, system.event_count())));
      std::vector<int> flags(events.size(), 1);
      system.initialize(context, 0.0, state.data());
      // first samples: buffers may fill lazily
      system.at_breakpoint(context, 0.0, 0.0, state.data());
      const long before = allocations.load();
      for (int k = 1; k < 400; ++k) {
        const double t = 0.025 * k;  // sample instants and PWM edges in between
        system.at_breakpoint(context, t, t, state.data());
        system.adapt_tolerances(context, absolute.data(), relative.data());
        if (system.event_count() > 0) {
          system.evaluate_events(context, t, t, state.data(), events.data());
          system.at_events(context, t, t, state.data(), flags.data());
        }
        (void)system.next_breakpoint_after(context, t);
      }
      const long allocated = allocations.load() - before;
      INFO(config << " " << fidelity);
      CHECK(allocated == 0);
    }
  }
}

TEST_CASE("Evaluating the right-hand side and the outputs allocates nothing") {
  for (const char* config :
       {"configs/ch7_identification.yaml", "configs/ch6_static_staircase.yaml"}) {
    Scenario scenario = load_scenario(source_path(config), {}, shared_units());
    const System& system = *scenario.system;
    Context context = scenario.make_context();
    std::vector<double>& state = context.state();
    std::vector<double> derivatives(state.size());
    system.initialize(context, 0.0, state.data());
    const long before = allocations.load();
    for (int k = 0; k < 1000; ++k) {
      const double t = 0.37 * k;
      system.evaluate_derivatives(context, t, t, state.data(), derivatives.data());
      system.evaluate_outputs(context, t, t, state.data());
      (void)system.next_breakpoint_after(context, t);
    }
    const long allocated = allocations.load() - before;
    INFO(config);
    CHECK(allocated == 0);
  }
}
