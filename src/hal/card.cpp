// Names of card faults, for messages and reports.
#include "gantry/hal/card.hpp"

namespace gantry {

const char* fault_name(CardFault f) {
  switch (f) {
    case CardFault::None:
      return "none";
    case CardFault::Underrun:
      return "underrun";
    case CardFault::EStop:
      return "E-stop";
    case CardFault::Limit:
      return "limit switch";
    case CardFault::Hardware:
      return "card failure";
  }
  return "?";
}

}  // namespace gantry
