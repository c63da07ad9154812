// Text inside markup: HTML pages (the reports), XML (JUnit, SVG charts), Markdown (summary.md)
// and relative paths written as URLs. Every page and file of the report escapes through these.
#pragma once

#include <string>
#include <string_view>

namespace twinrender::report {

// Text for HTML, in text nodes and quoted attributes alike: & < > " ' escaped.
std::string htmlEscape(std::string_view text);

// Text for XML: & < > escaped, and " too inside attributes (`attribute`), where newlines and
// tabs become character references; carriage returns are dropped and other control
// characters, which XML 1.0 does not allow, become spaces.
std::string xmlEscape(std::string_view text, bool attribute);

// Text for Markdown (CommonMark and GitHub's), in a paragraph or a table cell: every
// character that could start emphasis, code, a link, HTML, a table column, math ($), a
// mention (@) or an issue reference (#) is escaped with a backslash; line breaks and tabs
// become spaces, so the text stays on its line.
std::string markdownEscape(std::string_view text);

// A relative path as a URL: every byte outside the unreserved set and '/' percent-encoded.
std::string urlPath(std::string_view path);

// The path a relative URL names: urlPath's inverse (every %XX decoded), for checking links.
std::string pathOfUrl(std::string_view url);

}  // namespace twinrender::report
