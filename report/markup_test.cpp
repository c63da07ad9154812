#include "report/markup.h"

#include <gtest/gtest.h>

namespace twinrender::report {
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

TEST(Markup, MarkdownEscapesWhatCouldBecomeMarkupAndKeepsTheLine) {
    EXPECT_EQ(markdownEscape("a|b *c* _d_ `e` [f](g) <h> ~i~ & $j$ #1 @k!\\"),
              "a\\|b \\*c\\* \\_d\\_ \\`e\\` \\[f\\](g) \\<h\\> \\~i\\~ \\& \\$j\\$ \\#1 "
              "\\@k\\!\\\\");
    EXPECT_EQ(markdownEscape("two\nlines\r\tand tab"), "two lines  and tab");
    EXPECT_EQ(markdownEscape("beauty.flip = 0.2 (t.toml:1:25) ꟻ°"),
              "beauty.flip = 0.2 (t.toml:1:25) ꟻ°");
}

TEST(Markup, UrlPathsKeepSlashesAndEncodeTheRest) {
    EXPECT_EQ(urlPath("a b&<c>/beauty #1.png"), "a%20b%26%3Cc%3E/beauty%20%231.png");
    EXPECT_EQ(urlPath("planet/realtime.beauty.png"), "planet/realtime.beauty.png");
}

}  // namespace
}  // namespace twinrender::report
