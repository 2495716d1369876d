#include "core/error.h"

#include "core/text.h"

namespace prt {

Error::Error(const std::string& message) : std::runtime_error(one_line(message)) {}

void fail_file(const std::string& path, const std::string& problem) { throw Error(path + ": " + problem); }

void fail(const std::string& problem) { throw Error(problem); }

}  // namespace prt
