#pragma once
// The limits every JSON file the workbench reads is held to, checked on the text before it is
// parsed, so that a hostile or broken file is refused by place instead of exhausting the stack,
// the memory or the patience of whoever runs it (docs/limits.md).
#include <cstddef>
#include <string>

namespace activetouch {

/// A JSON file larger than this is refused before it is read: experiment, scene, rig and
/// fingertip files are a few kilobytes; an outline of the largest accepted vertex count is
/// well under a megabyte.
inline constexpr std::size_t kMaxJsonFileBytes = 16u << 20;
/// Objects and lists nested deeper than this are refused: the deepest real file nests five.
inline constexpr int kMaxJsonDepth = 64;

/// Checks `text` before parsing: nesting no deeper than kMaxJsonDepth, no key twice in one
/// object, no number beyond the range of a double. Throws InputError naming `source`, the line
/// and column (and the JSON pointer of a repeated key with both places). Text that is not JSON
/// at all is left for the parser to describe.
void checkJsonText(const std::string& text, const std::string& source);

/// Reads at most kMaxJsonFileBytes from `path` (a longer file, or a device that never ends, is
/// an InputError naming it).
std::string readJsonFileText(const std::string& path);

}  // namespace activetouch
