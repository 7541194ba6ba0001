// A bar's note name as a visitor reads it.
#include "core/note_name.hpp"

#include <gtest/gtest.h>

#include "test_paths.hpp"

namespace mallet {
namespace {

TEST(NoteName, ScientificPitchNotationWithSharpsAsHashes) {
  EXPECT_EQ(note_name(60), "C4");
  EXPECT_EQ(note_name(69), "A4");
  EXPECT_EQ(note_name(72), "C5");
  EXPECT_EQ(note_name(73), "C#5");
  EXPECT_EQ(note_name(71), "B4");
  EXPECT_EQ(note_name(0), "C-1");
  EXPECT_EQ(note_name(127), "G9");
}

TEST(NoteName, TheShippedXylophoneIsAnOctaveFromC5) {
  const Scene& s = test::percussion();
  const Instrument& xylophone = s.instruments.at(0);
  std::string names;
  for (int id : xylophone.targets) names += note_name(s.targets.at(static_cast<std::size_t>(id)).note) + " ";
  EXPECT_EQ(names, "C5 D5 E5 F5 G5 A5 B5 C6 ");
}

}  // namespace
}  // namespace mallet
