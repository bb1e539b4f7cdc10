// Error types shared by every rockfit library. Each maps to one exit code of the `rockfit` program
// (docs/design.md §9): usage 1, bad input data 2, numerical failure 3, cannot write output 4.
#pragma once

#include <stdexcept>
#include <string>

namespace rockfit {

// A caller passed an argument outside its allowed range (exit code 1).
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Input data (a file, a manifest) cannot be used as it is (exit code 2).
// The message names the file, line and column where known, what was found and what to do.
class BadInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A computation could not produce a meaningful result (exit code 3).
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output file could not be written (exit code 4). Existing files are left untouched.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rockfit
