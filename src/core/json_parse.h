#pragma once
// The one way prt parses a JSON document it reads from a user's file: the nesting guard first
// (core/json_depth.h), then nlohmann-json, with its errors turned into prt's one line.
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_depth.h"

namespace prt {

/// Parses `text` (the contents of the file `path`). Throws prt::Error("<path>: JSON nested deeper
/// than ...") before parsing a document nested over kMaxJsonDepth levels, and
/// prt::Error("<path>: not valid JSON: <parser's reason>") for a syntax error or a number out of
/// double's range (1e999). Does not check the document's shape.
inline nlohmann::json parse_json(const std::string& text, const std::string& path) {
  check_json_depth(text, path);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range for 1e999
    fail_file(path, std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace prt
