// A small XML well-formedness check for tests: elements nest and close in order, attributes
// are quoted and unique, entities are the five predefined ones or numeric, one root element.
// Not a full parser (no DTDs); enough to catch what a hand-written SVG writer gets wrong.
#pragma once

#include <cctype>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace twinrender::test {

struct XmlCheck {
    std::string error;                         // empty when well-formed
    std::map<std::string, int> elementCounts;  // element name -> how many
    std::map<std::string, int> classCounts;    // each word of class="..." -> how many elements
};

inline XmlCheck checkXml(const std::string& s) {
    XmlCheck r;
    std::vector<std::string> stack;
    int roots = 0;
    auto fail = [&](const std::string& what, std::size_t at) {
        r.error = what + " at offset " + std::to_string(at);
        return r;
    };
    auto checkEntities = [&](const std::string& text, std::size_t at) -> bool {
        for (std::size_t i = 0; i < text.size(); ++i) {
            if (text[i] == '<') {
                fail("'<' in text or attribute", at + i);
                return false;
            }
            if (text[i] != '&') continue;
            const std::size_t semi = text.find(';', i);
            if (semi == std::string::npos) {
                fail("unterminated entity", at + i);
                return false;
            }
            const std::string e = text.substr(i + 1, semi - i - 1);
            static const std::set<std::string> known = {"amp", "lt", "gt", "quot", "apos"};
            if (!known.count(e) && !(e.size() > 1 && e[0] == '#')) {
                fail("unknown entity &" + e + ";", at + i);
                return false;
            }
        }
        return true;
    };
    std::size_t i = 0;
    while (i < s.size()) {
        if (s[i] != '<') {
            const std::size_t next = s.find('<', i);
            const std::string text = s.substr(i, next - i);
            if (!checkEntities(text, i)) return r;
            if (stack.empty() && text.find_first_not_of(" \t\r\n") != std::string::npos)
                return fail("text outside the root element", i);
            i = next == std::string::npos ? s.size() : next;
            continue;
        }
        if (s.compare(i, 5, "<?xml") == 0) {
            if (i != 0) return fail("XML declaration not at the start", i);
            const std::size_t end = s.find("?>", i);
            if (end == std::string::npos) return fail("unterminated declaration", i);
            i = end + 2;
            continue;
        }
        if (s.compare(i, 4, "<!--") == 0) {
            const std::size_t end = s.find("-->", i);
            if (end == std::string::npos) return fail("unterminated comment", i);
            i = end + 3;
            continue;
        }
        const std::size_t end = s.find('>', i);
        if (end == std::string::npos) return fail("unterminated tag", i);
        std::string tag = s.substr(i + 1, end - i - 1);
        if (!tag.empty() && tag[0] == '/') {
            const std::string name = tag.substr(1);
            if (stack.empty() || stack.back() != name)
                return fail("</" + name + "> does not close the open element", i);
            stack.pop_back();
            i = end + 1;
            continue;
        }
        const bool selfClosing = !tag.empty() && tag.back() == '/';
        if (selfClosing) tag.pop_back();
        std::size_t p = 0;
        while (p < tag.size() && !std::isspace(static_cast<unsigned char>(tag[p]))) ++p;
        const std::string name = tag.substr(0, p);
        if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_'))
            return fail("bad element name '" + name + "'", i);
        // Attributes: name="value" or name='value'.
        std::set<std::string> seen;
        while (true) {
            while (p < tag.size() && std::isspace(static_cast<unsigned char>(tag[p]))) ++p;
            if (p >= tag.size()) break;
            const std::size_t eq = tag.find('=', p);
            if (eq == std::string::npos)
                return fail("attribute without a value in <" + name + ">", i);
            const std::string attr = tag.substr(p, eq - p);
            if (attr.empty() || attr.find_first_of(" \t\n\"'") != std::string::npos)
                return fail("bad attribute name in <" + name + ">", i);
            if (!seen.insert(attr).second)
                return fail("attribute " + attr + " twice in <" + name + ">", i);
            if (eq + 1 >= tag.size() || (tag[eq + 1] != '"' && tag[eq + 1] != '\''))
                return fail("unquoted attribute " + attr, i);
            const char q = tag[eq + 1];
            const std::size_t close = tag.find(q, eq + 2);
            if (close == std::string::npos) return fail("unterminated attribute " + attr, i);
            const std::string value = tag.substr(eq + 2, close - eq - 2);
            if (!checkEntities(value, i)) return r;
            if (attr == "class") {
                std::size_t a = 0;
                while (a < value.size()) {
                    std::size_t b = value.find(' ', a);
                    if (b == std::string::npos) b = value.size();
                    if (b > a) ++r.classCounts[value.substr(a, b - a)];
                    a = b + 1;
                }
            }
            p = close + 1;
        }
        ++r.elementCounts[name];
        if (stack.empty() && ++roots > 1) return fail("a second root element <" + name + ">", i);
        if (!selfClosing) stack.push_back(name);
        i = end + 1;
    }
    if (!stack.empty()) return fail("<" + stack.back() + "> is never closed", s.size());
    if (roots == 0) return fail("no root element", 0);
    return r;
}

}  // namespace twinrender::test
