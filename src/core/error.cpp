#include "core/error.h"

#include "core/text.h"

namespace prt {

Error::Error(const std::string& message) : std::runtime_error(one_line(message)) {}

void fail_file(const std::string& path, const std::string& problem) { throw Error(path + ": " + problem); }

OptionError::OptionError(const std::string& file, const std::string& field, const std::string& rest)
    : Error((file.empty() ? "" : file + ": ") + field + rest), file_(one_line(file)), field_(field), rest_(one_line(rest)) {}

void fail(const std::string& problem) { throw Error(problem); }

void fail_option(const std::string& field, const std::string& rest) { throw OptionError("", field, rest); }

void fail_file_option(const std::string& path, const std::string& field, const std::string& rest) {
  throw OptionError(path, field, rest);
}

}  // namespace prt
