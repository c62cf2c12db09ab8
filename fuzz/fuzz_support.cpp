#include "fuzz/fuzz_support.h"

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "sim/config/config_error.h"
#include "sim/config/units.h"
#include "sim/parameters.h"

namespace tcpmsim::fuzz {

void expect_clean_outcome(const std::function<void()>& parse) {
  try {
    parse();
  } catch (const ConfigError&) {
  } catch (const UnitError&) {
  } catch (const ParameterError&) {
  } catch (const UsageError&) {
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fuzz: an input reached the user as an internal error: %s\n",
                 error.what());
    std::abort();
  }
}

std::string text_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace tcpmsim::fuzz
