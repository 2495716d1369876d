#include "core/error.h"

namespace prt {

namespace {
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}
}  // namespace

Error::Error(const std::string& message) : std::runtime_error(one_line(message)) {}

void fail_file(const std::string& path, const std::string& problem) { throw Error(path + ": " + problem); }

void fail(const std::string& problem) { throw Error(problem); }

}  // namespace prt
