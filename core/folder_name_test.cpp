#include "core/folder_name.h"

#include <gtest/gtest.h>

#include <string>

namespace tc = twinrender::core;

TEST(FolderName, OrdinaryNamesAreFolderNames) {
    for (const char* name : {"planet", "splash_sheet", "Planet (v2) + ring", "a.b-c", "COM0",
                             "console", "nul-ish", "Ünïcode ☄", ".hidden"})
        EXPECT_EQ(tc::folderNameProblem(name), "") << name;
    EXPECT_EQ(tc::folderNameProblem(std::string(100, 'x')), "");
}

TEST(FolderName, PathsAndUnsafeNamesAreRefusedWithTheirReason) {
    const auto problem = [](std::string_view name) { return tc::folderNameProblem(name); };
    EXPECT_EQ(problem(""), "is empty");
    EXPECT_NE(problem(".").find("names a folder already"), std::string::npos);
    EXPECT_NE(problem("..").find("names a folder already"), std::string::npos);
    EXPECT_NE(problem("../../escaped").find("path separator '/'"), std::string::npos);
    EXPECT_NE(problem("a\\b").find("path separator '\\'"), std::string::npos);
    EXPECT_NE(problem("/abs").find("path separator"), std::string::npos);
    EXPECT_NE(problem(std::string("a\0b", 3)).find("control character \\x00"), std::string::npos);
    EXPECT_NE(problem("tab\there").find("\\x09"), std::string::npos);
    EXPECT_NE(problem("del\x7f").find("\\x7f"), std::string::npos);
    EXPECT_NE(problem("x<script>alert(1)</script>").find("'<'"), std::string::npos);
    for (const char* c : {"a:b", "a\"b", "a|b", "a?b", "a*b", "a>b"})
        EXPECT_NE(problem(c).find("Windows refuses"), std::string::npos) << c;
    EXPECT_NE(problem("trailing.").find("ends in a dot"), std::string::npos);
    EXPECT_NE(problem("trailing ").find("ends in a dot or a space"), std::string::npos);
    for (const char* d : {"CON", "con", "Nul.txt", "prn", "AUX", "com1", "LPT9.log"})
        EXPECT_NE(problem(d).find("device name"), std::string::npos) << d;
    EXPECT_NE(problem(std::string(101, 'x')).find("101 bytes"), std::string::npos);
    EXPECT_EQ(problem("\xff\xfe"), "is not valid UTF-8");
    EXPECT_EQ(problem("\xc3"), "is not valid UTF-8");          // cut short
    EXPECT_EQ(problem("\xc0\xaf"), "is not valid UTF-8");      // an overlong '/'
    EXPECT_EQ(problem("\xed\xa0\x80"), "is not valid UTF-8");  // a surrogate
}

TEST(FolderName, NamesDifferingOnlyInAsciiCaseShareAKey) {
    EXPECT_EQ(tc::folderNameKey("Planet"), tc::folderNameKey("pLANET"));
    EXPECT_NE(tc::folderNameKey("planet"), tc::folderNameKey("planet2"));
    EXPECT_EQ(tc::folderNameKey("Ä"), "Ä");  // letters outside ASCII as written
}

TEST(FolderName, PrintableEscapesControlBytesAndCutsLongText) {
    EXPECT_EQ(tc::printable(std::string("a\0b\n", 4)), "a\\x00b\\x0a");
    EXPECT_EQ(tc::printable("\xff"), "\\xff");
    EXPECT_EQ(tc::printable("Ünï"), "Ünï");
    EXPECT_EQ(tc::printable(std::string(10, 'x'), 4), "xxxx...");
}
