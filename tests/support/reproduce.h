// The command line that evaluates a membrane or shell tube as a test evaluated it, for the message of
// a failing check: every setting the tests change, numbers at 17 digits, and only options that apply
// (the command line refuses the others). The self-intersection check has no option: where a test
// turns it off, the line says so after a '#'.
#pragma once

#include <string>

#include "sim/model.h"

namespace testing_support {

std::string ReproduceCommand(const sim::EvalJob& job);

}  // namespace testing_support
