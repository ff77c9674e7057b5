// Procedural "RunProgram": talking to a helper program the RenderMan way.
//
// The program is started once per distinct command line and kept running. For each expansion
// streyes writes "detail datablock\n" to its standard input; the program answers with RIB on its
// standard output, ending the answer with the byte \377 (a program that exits instead also ends
// its answer; the next request starts it again). Its standard error passes through to ours.
#pragma once

#include <string>
#include <vector>

#include "streyes/error.h"

namespace streyes {

// The RIB a program produces for one request. Throws InputError naming `loc` when the program
// cannot be started, exits with an error, or does not answer within `timeoutSeconds`.
std::string runProgramRequest(const std::string& commandLine, double detail, const std::string& datablock,
                              const SourceLoc& loc, double timeoutSeconds = 60);

// The program's path when it can be run (searched in PATH like a shell), else "".
std::string findProgram(const std::string& name);

// Splits a command line on white space (no quoting: arguments with spaces are not supported).
std::vector<std::string> splitCommandLine(const std::string& commandLine);

}  // namespace streyes
