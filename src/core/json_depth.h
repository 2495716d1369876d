#pragma once
// A guard run on JSON text before any JSON library parses it. Parsers and the code walking the
// parsed tree (nlohmann's dump(), tinygltf's value conversion) recurse once per level of nesting, so
// a small file nested tens of thousands of levels deep overflows the stack. Every JSON that prt reads
// (SH lighting, probe headers, points, BRDF files, glTF) passes through check_json_depth first.
#include <string>
#include <string_view>

namespace prt {

/// Deepest nesting of arrays and objects prt accepts in any JSON it reads (docs/formats.md, "Limits").
inline constexpr int kMaxJsonDepth = 64;

/// Throws prt::Error("<name>: JSON nested deeper than <max_depth> levels (at byte B)") if `text`
/// opens more than `max_depth` arrays/objects inside one another. Brackets inside strings (with
/// backslash escapes) are not counted. Does not otherwise validate the text; O(text size).
void check_json_depth(std::string_view text, const std::string& name, int max_depth = kMaxJsonDepth);

}  // namespace prt
