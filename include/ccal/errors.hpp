#pragma once
// Exceptions for problems in what the user gave ccal (configuration, data files, command line), as opposed
// to programming errors. The CLI catches InputError to print the message without a stack of internals.
#include <stdexcept>

namespace ccal {

// Anything the user supplied that ccal cannot accept. The message is meant for the user: it names the
// offending item and, where possible, says what would have been accepted.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A quantity or unit that cannot be parsed, has the wrong dimension, or is not a finite number.
class UnitError : public InputError {
 public:
  using InputError::InputError;
};

}  // namespace ccal
