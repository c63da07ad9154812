// Names that become folder names. A scene's name names its output folder (`OUT/<name>/`), and
// a scene file travels in pull requests and bug reports: the name must be one folder name on
// every system the report may be opened on, never a path.
//
// A folder name here is 1 to 100 bytes of UTF-8 with
//   - no path separator (/ or \), no control character (U+0000 to U+001F, U+007F),
//   - none of < > : " | ? * (Windows refuses them),
//   - not "." or "..", not ending in a dot or a space (Windows drops those),
//   - not a Windows device name (CON, PRN, AUX, NUL, COM1-COM9, LPT1-LPT9, with or without an
//     extension: "nul.txt" names the device too).
// Two names that differ only in the case of ASCII letters name one folder on macOS and Windows
// (folderNameKey); letters outside ASCII are compared as written.
#pragma once

#include <string>
#include <string_view>

namespace twinrender::core {

// Why `name` cannot be a folder name ("contains a path separator '/'"), or empty when it can.
std::string folderNameProblem(std::string_view name);

// What a folder name must be, in one sentence for messages.
std::string_view folderNameRule();

// The form in which two names that one folder would hold compare equal: ASCII letters in
// lower case.
std::string folderNameKey(std::string_view name);

// `text` for a message: control characters and bytes that are not UTF-8 as \xNN, at most
// `limit` bytes of it and then "...".
std::string printable(std::string_view text, std::size_t limit = 120);

}  // namespace twinrender::core
