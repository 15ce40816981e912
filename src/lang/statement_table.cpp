// The keyword statements' table: the parser's dispatch, `help` and the docs test read it.
#include "gantry/lang/statement_table.hpp"

#include <algorithm>  // find_if

#include "gantry/lang/scan.hpp"  // upper

namespace gantry {
namespace {

// clang-format off
constexpr StatementSpec kStatements[] = {
  {"GOTO", Keyword::Goto, "Continue at a label",
   "GOTO label            continues at the line after label: in this file", "4.2"},
  {"GOSUB", Keyword::Gosub, "Call a subroutine at a label",
   "GOSUB label           jumps to label: and remembers the next line (256 deep at most)", "4.3"},
  {"RETURN", Keyword::Return, "Return from a subroutine",
   "RETURN                goes back to the line after the last GOSUB", "4.3"},
  {"END", Keyword::End, "End this file",
   "END                   ends this file (a file called by FP returns to its caller)\n"
   "END \"message\"         prints the message, then ends (FabMo)", "4.4"},
  {"ENDALL", Keyword::EndAll, "End every file",
   "ENDALL                ends this file and every file that called it", "4.4"},
  {"EXIT", Keyword::Exit, "End every file (SB3)",
   "EXIT SHOPBOT          as ENDALL", "4.4"},
  {"IF", Keyword::If, "Run one statement when a test holds",
   "IF test THEN statement   the statement runs when the test is not 0 (no ELSE, no block IF)",
   "4.5"},
  {"ON", Keyword::On, "Act when an input switch changes",
   "ON INPUT(switch, state) statement   runs it when input 1-12 changes to state\n"
   "                                    (0 opens, 1 closes; 2, 3 the same with a ramped stop)\n"
   "ON INPUT(switch, state)             clears the handler", "4.6"},
  {"PAUSE", Keyword::Pause, "Wait for the operator, a time or an input switch",
   "PAUSE                 waits for the operator; the comment line above is the message\n"
   "PAUSE seconds         waits that long in the motion stream\n"
   "PAUSE \"message\"       waits for the operator with that message\n"
   "PAUSE \"message\", &var asks the operator and stores the answer\n"
   "PAUSE UNTIL switch, state   waits until input 1-12 is closed (1) or open (0)", "4.7"},
  {"PRINT", Keyword::Print, "Print values on the screen, or to an open file",
   "PRINT item, item      items five spaces apart\n"
   "PRINT item; item      items joined; a ; at the end keeps the line open\n"
   "PRINT #n, item        as WRITE #n", "4.9"},
  {"WRITE", Keyword::Write, "Write values to an open file",
   "WRITE #n, item, item  items joined with \", \"\n"
   "WRITE #n; item; item  items joined", "4.9"},
  {"INPUT", Keyword::Input, "Ask the operator for values, or read a line of a file",
   "INPUT \"prompt\" &v {, &v}          asks; several variables split the answer at commas\n"
   "INPUT \"prompt\" : &default, &v     offers &default's value\n"
   "INPUT #n, &v {, &v}               reads the next line of a file opened FOR INPUT", "4.8"},
  {"MSGBOX", Keyword::Msgbox, "Ask with buttons; the answer is in &MSGANSWER",
   "MSGBOX(text, buttons, title)   buttons: OKOnly, OKCancel, YesNo, YesNoCancel,\n"
   "                               AbortRetryIgnore, RetryCancel (or 0-5, + 256 second default)",
   "4.12"},
  {"DIALOG", Keyword::Dialog, "Show a message and wait for the operator (FabMo)",
   "DIALOG message {, NAME = value}   OKTEXT, CANCELTEXT, TITLE, TIMER = seconds", "4.13"},
  {"FAIL", Keyword::Fail, "Stop the run with an error (FabMo)",
   "FAIL {message}        stops the run: FAIL: message", "4.13"},
  {"OPEN", Keyword::Open, "Open a file to read or write",
   "OPEN path FOR INPUT|OUTPUT|APPEND AS #n   n is 1 to 9", "4.10"},
  {"CLOSE", Keyword::Close, "Close an open file",
   "CLOSE #n              closes file n\n"
   "CLOSE                 closes them all", "4.10"},
  {"SHELL", Keyword::Shell, "Run another program (needs --allow-shell)",
   "SHELL, command {, display} {, SYNC|ASYNC}   ASYNC (the default) does not wait", "4.14"},
  {"WARNING", Keyword::Warning, "Accepted; no effect (SB3)",
   "WARNING OFF", "4.16"},
  {"PLAY", Keyword::Play, "Accepted; Gantry plays no sound and warns",
   "PLAY path", "4.15"},
  {"SETUSRVAL", Keyword::Registry, "Keep a value between runs (SB3 registry)",
   "SetUsrVal, value", "4.17"},
  {"SETUSRVALCLRD", Keyword::Registry, "Keep a value for this run's called files",
   "SetUsrValClrd, value", "4.17"},
  {"SETSPINDLESTATUS", Keyword::Registry, "Record the spindle status (no other effect)",
   "SetSpindleStatus, 0|1", "4.17"},
  {"GETUSRVAL", Keyword::Registry, "Read the value SetUsrVal kept",
   "GetUsrVal, &v", "4.17"},
  {"GETUSRVALCLRD", Keyword::Registry, "Read the value SetUsrValClrd kept in this run",
   "GetUsrValClrd, &v", "4.17"},
  {"GETSPINDLESTATUS", Keyword::Registry, "Read the recorded spindle status",
   "GetSpindleStatus, &v", "4.17"},
  {"GETUSRPATH", Keyword::Registry, "The folder of the persistent file",
   "GetUsrPath, &v", "4.17"},
  {"GETAPPPATH", Keyword::Registry, "The folder of the gantry program",
   "GetAppPath, &v", "4.17"},
  {"GETPARTFILENAME", Keyword::Registry, "The top-level part file's name",
   "GetPartFileName, &v", "4.17"},
  {"DATA_SEND", Keyword::DataSend, "Refused: FabMo's dashboard statement (use PRINT or WRITE #n)",
   "DATA_SEND ...", "7"},
};
// clang-format on

}  // namespace

std::span<const StatementSpec> statement_table() {
  return kStatements;
}

const StatementSpec* find_statement(std::string_view word) {
  const std::string up = scan::upper(word);
  const StatementSpec* s = std::find_if(std::begin(kStatements), std::end(kStatements),
                                        [&](const StatementSpec& r) { return r.word == up; });
  return s == std::end(kStatements) ? nullptr : s;
}

}  // namespace gantry
