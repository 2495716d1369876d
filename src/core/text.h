#pragma once
// Small string helpers shared by every module that picks a file format from a path.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace prt {

/// `s` with ASCII letters in lower case (other bytes unchanged).
inline std::string to_lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// `s` on one line: line breaks become spaces, trailing spaces are dropped (error messages of libraries).
inline std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

/// The first line of `text` (up to its first '\n'), trailing '\r' and spaces dropped: a library's
/// multi-line message cut to the line that names the problem.
inline std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

/// The extension of the last path component, dot included, in lower case: ".ply" for "a/B.PLY", "" for
/// "a.d/file" or "file" (std::filesystem::path::extension).
inline std::string lower_extension(const std::string& path) {
  return to_lower(std::filesystem::path(path).extension().string());
}

}  // namespace prt
