#include <deme/Error.h>

namespace deme {

void throwError(const std::string& call, const std::string& message) { throw Error(call + ": " + message); }

void throwFileError(const std::string& call, const std::string& file, size_t line, const std::string& message) {
    throw Error(call + ": " + file + ":" + std::to_string(line) + ": " + message);
}

}  // namespace deme
