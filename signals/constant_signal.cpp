#include "signals/constant_signal.h"

namespace tcpmsim {

SignalDescription ConstantSignal::describe() const {
  return {"constant", {{"value", value_}}, {}, {}};
}

}  // namespace tcpmsim
