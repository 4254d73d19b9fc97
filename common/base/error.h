// Error types shared by both programs.
//
// Two kinds of failure reach the user (DESIGN.md, "Contracts"):
//   * InputError: the user's input is wrong (bad YAML, a value out of range, a missing
//     file). The programs exit with code 2. The message names the file, the key and the
//     YAML line, says what was expected and what was found.
//   * ComputeError: a computation failed (a factorisation, an eigen solver, the time
//     integrator). The programs exit with code 1. The message says what failed and where.
// Internal invariants use FFRIGA_ASSERT (debug builds only); anything a user can cause is
// checked always and throws one of the two types above.
#pragma once

#include <cassert>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace ffriga {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// An input error found while computing, about one parameter of the input file: `key` its
// path as errors name it ("reduction.normal_modes", "contact.region"). The program that
// read the file rethrows it with the file and the key's YAML line
// (common/input/yaml_input.h: inputErrorAt); what() alone reads "key 'KEY': MESSAGE".
class ParameterError : public InputError {
 public:
  ParameterError(std::string key, const std::string& message)
      : InputError("key '" + key + "': " + message), key_(std::move(key)), message_(message) {}
  const std::string& key() const { return key_; }
  const std::string& message() const { return message_; }

 private:
  std::string key_, message_;
};

class ComputeError : public std::runtime_error {
 public:
  explicit ComputeError(const std::string& message) : std::runtime_error(message) {}
};

// Builds a message from any streamable values: Str() << "n = " << n.
class Str {
 public:
  template <typename T>
  Str& operator<<(const T& value) {
    stream_ << value;
    return *this;
  }
  operator std::string() const { return stream_.str(); }
  std::string str() const { return stream_.str(); }

 private:
  std::ostringstream stream_;
};

}  // namespace ffriga

// Always-on check of a condition a caller can violate; throws std::invalid_argument with
// the location and the message. Use InputError for user input instead.
#define FFRIGA_CHECK(cond, msg)                                                            \
  do {                                                                                     \
    if (!(cond)) {                                                                         \
      throw std::invalid_argument(::ffriga::Str() << __FILE__ << ":" << __LINE__ << ": "   \
                                                  << "check '" #cond "' failed: " << msg); \
    }                                                                                      \
  } while (0)

#ifdef NDEBUG
#define FFRIGA_ASSERT(cond, msg) ((void)0)
#else
#define FFRIGA_ASSERT(cond, msg) FFRIGA_CHECK(cond, msg)
#endif
