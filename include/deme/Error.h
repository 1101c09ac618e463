// The one exception type the engine throws at its users.
#pragma once

#include <stdexcept>
#include <string>

namespace deme {

// Every message names the API call that failed; input from files also names file:line.
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// Throws Error("<call>: <message>").
[[noreturn]] void throwError(const std::string& call, const std::string& message);
// Throws Error("<call>: <file>:<line>: <message>").
[[noreturn]] void throwFileError(const std::string& call, const std::string& file, size_t line,
                                 const std::string& message);

}  // namespace deme
