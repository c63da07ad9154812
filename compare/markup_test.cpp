#include "compare/markup.h"

#include <gtest/gtest.h>

namespace twinrender::compare {
namespace {

TEST(Markup, HtmlEscapesTheFiveReservedCharacters) {
    EXPECT_EQ(htmlEscape("a<b> & \"c\" 'd'\n"), "a&lt;b&gt; &amp; &quot;c&quot; &#39;d&#39;\n");
    EXPECT_EQ(htmlEscape("ꟻLIP °"), "ꟻLIP °");  // UTF-8 as it is
}

TEST(Markup, XmlEscapesTextAndAttributesApart) {
    EXPECT_EQ(xmlEscape("a<b> & \"c\"\n\td\r", false), "a&lt;b&gt; &amp; \"c\"\n\td");
    EXPECT_EQ(xmlEscape("a<b> & \"c\"\n\td\r", true), "a&lt;b&gt; &amp; &quot;c&quot;&#10;&#9;d");
    EXPECT_EQ(xmlEscape(std::string("x\x01y'"), false), "x y'");  // not allowed in XML 1.0
}

TEST(Markup, UrlPathsKeepSlashesAndEncodeTheRest) {
    EXPECT_EQ(urlPath("a b&<c>/beauty #1.png"), "a%20b%26%3Cc%3E/beauty%20%231.png");
    EXPECT_EQ(urlPath("planet/realtime.beauty.png"), "planet/realtime.beauty.png");
}

}  // namespace
}  // namespace twinrender::compare
