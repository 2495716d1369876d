#pragma once
// Errors that reach the user. Every failure caused by input (a file, an argument) is reported as one
// line: "<file>: <problem>" when a file is involved, else "<problem>". The CLI prints it after "prt: "
// and exits with status 1.
#include <stdexcept>
#include <string>

namespace prt {

/// A user-facing failure with a one-line message (no trailing newline).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message);
};

/// A failure of one field of an options struct (a value out of range, a malformed spec): what() is
/// field() followed by rest(), e.g. "samples" and " 0 is out of range 1..1048576", after "<file>: "
/// when the option is judged against a file. Library code names the struct's field; a program maps the
/// field to its own spelling (the CLI: "--samples 0 is ...").
class OptionError : public Error {
 public:
  OptionError(const std::string& file, const std::string& field, const std::string& rest);
  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& rest() const { return rest_; }

 private:
  std::string file_, field_, rest_;
};

/// Throws Error("<path>: <problem>").
[[noreturn]] void fail_file(const std::string& path, const std::string& problem);

/// Throws OptionError("", field, rest): `rest` starts with its own separator (" 0 is ...", ": expected ...").
[[noreturn]] void fail_option(const std::string& field, const std::string& rest);

/// Throws OptionError(path, field, rest): an option that does not fit the file at `path`.
[[noreturn]] void fail_file_option(const std::string& path, const std::string& field, const std::string& rest);

/// Throws Error(problem).
[[noreturn]] void fail(const std::string& problem);

}  // namespace prt
