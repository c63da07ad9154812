// Text inside markup: HTML pages (the reports), XML (JUnit, SVG charts) and relative paths
// written as URLs. Every page and file of the report escapes through these.
#pragma once

#include <string>
#include <string_view>

namespace twinrender::compare {

// Text for HTML, in text nodes and quoted attributes alike: & < > " ' escaped.
std::string htmlEscape(std::string_view text);

// Text for XML: & < > escaped, and " too inside attributes (`attribute`), where newlines and
// tabs become character references; carriage returns are dropped and other control
// characters, which XML 1.0 does not allow, become spaces.
std::string xmlEscape(std::string_view text, bool attribute);

// A relative path as a URL: every byte outside the unreserved set and '/' percent-encoded.
std::string urlPath(std::string_view path);

}  // namespace twinrender::compare
