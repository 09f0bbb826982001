// Errors that reach the user: invalid input and failed I/O.
//
// Every message names what was wrong and where (file, keyword, line or byte
// offset), so that a user can fix the input without a debugger.
#pragma once

#include <stdexcept>
#include <string>

namespace metrica {

// The input (a file, a mesh, an option value) is invalid.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A file could not be read or written, or is malformed.
class IoError : public InputError {
 public:
  using InputError::InputError;
};

// An error already printed where it happened (on another MPI rank, or by
// the rank itself with its number): the command exits 1 and prints nothing
// more.
class AlreadyReported : public std::runtime_error {
 public:
  AlreadyReported() : std::runtime_error("failed (reported above)") {}
};

}  // namespace metrica
