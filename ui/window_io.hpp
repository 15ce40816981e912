// The operator as the console window is one: the session's mailbox (session/operator_io.hpp).
// PRINT text and warnings go to the message log, and PAUSE, INPUT and MSGBOX become dialogs.
#pragma once

#include "gantry/session/operator_io.hpp"  // OperatorMailbox, Question

namespace gantry::ui {

using Question = session::Question;
using WindowIO = session::OperatorMailbox;

}  // namespace gantry::ui
