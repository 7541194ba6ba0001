// The one CSV reader (core/csv_file.hpp): what every file the project reads goes through,
// and the one wording of its problems.
#include <gtest/gtest.h>

#include "core/csv_file.hpp"
#include "core/file_error.hpp"

namespace mallet::csv {
namespace {

std::string error_of(std::string_view text, Options o = {}) {
  try {
    const Table t = parse(text, "f.csv", o);
    (void)t.column("b", "the header must name a,b");
    for (const Row& r : t.rows) (void)t.number(r, t.column("b"), "b");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

TEST(CsvFile, AHeaderThenRowsWithTheirLines) {
  const Table t = parse("a,b\r\n1,2\n\n3,4\n", "f.csv");
  EXPECT_EQ(t.header, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(t.header_line, 1u);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[1].line, 4u);  // the blank line counts
  EXPECT_EQ(t.rows[1][1], "4");
  EXPECT_EQ(t.number(1, 0), 3.0);
  EXPECT_EQ(t.column("b"), 1u);
  EXPECT_FALSE(t.find("c"));
  EXPECT_EQ(t.complete_bytes, 14u);
}

TEST(CsvFile, HandWrittenFilesHaveCommentsAndSpaces) {
  const Table t = parse("# points\n  a , b \n\t1, 2 ,3\n", "f.csv", {.hand_written = true, .extra_fields = true});
  EXPECT_EQ(t.header, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(t.header_line, 2u);
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.rows[0][0], "1");
  EXPECT_EQ(t.rows[0][1], "2");
  EXPECT_EQ(t.rows[0].fields.size(), 3u);  // an extra field, kept and ignored
  // In a file the program writes, '#' is data and spaces are kept.
  EXPECT_EQ(parse("a\n#1\n", "f.csv").rows.at(0)[0], "#1");
}

TEST(CsvFile, EveryProblemIsFileLineAndOneWording) {
  EXPECT_EQ(error_of("a,b\n1\n"), "f.csv:2: expected 2 fields, got 1");
  EXPECT_EQ(error_of("a,b\n1,2,3\n"), "f.csv:2: expected 2 fields, got 3");
  EXPECT_EQ(error_of("a,b\n1,2,3\n", {.extra_fields = true}), "");
  EXPECT_EQ(error_of("a,b\n1,x\n"), "f.csv:2: b: \"x\" is not a number");
  EXPECT_EQ(error_of("\n# c\na,c\n", {.hand_written = true}), "f.csv:3: missing column \"b\" (the header must name a,b)");
  EXPECT_EQ(error_of(""), "f.csv: empty file (no header line)");
}

TEST(CsvFile, AnIncompleteLastLineIsDroppedWithAWarningWhereTheProgramAppends) {
  const Table t = parse("a,b\n1,2\n3,", "f.csv", {.incomplete_last_line = true});
  EXPECT_EQ(t.rows.size(), 1u);
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_EQ(t.warnings[0], "f.csv:3: incomplete last line ignored (the program stopped while writing it)");
  EXPECT_EQ(t.complete_bytes, 8u);
  // Elsewhere the last line needs no '\n'.
  EXPECT_EQ(parse("a,b\n1,2\n3,4", "f.csv").rows.size(), 2u);
}

}  // namespace
}  // namespace mallet::csv
