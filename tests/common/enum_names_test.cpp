// EnumName tables: name_of and value_of read the same table, so every name written parses
// back to its value, aliases parse but are never written, and unknowns are reported.
#include "pgmcl/common/enum_names.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string_view>

namespace pgmcl {
namespace {

enum class Colour { kRed, kGreen, kBlue };

constexpr std::array<EnumName<Colour>, 3> kColours{{
    {Colour::kRed, "red"},
    {Colour::kGreen, "green"},
    {Colour::kRed, "crimson"},  // an alias: read, never written
}};

TEST(EnumNames, EveryWrittenNameParsesBack) {
  for (const Colour c : {Colour::kRed, Colour::kGreen}) {
    EXPECT_EQ(value_of(name_of(c, kColours), kColours), c);
  }
  EXPECT_STREQ(name_of(Colour::kRed, kColours), "red");
}

TEST(EnumNames, AliasesParseButAreNotWritten) {
  EXPECT_EQ(value_of("crimson", kColours), Colour::kRed);
  EXPECT_STREQ(name_of(value_of("crimson", kColours).value(), kColours), "red");
}

TEST(EnumNames, UnknownsGiveTheFallbackAndNullopt) {
  EXPECT_STREQ(name_of(Colour::kBlue, kColours), "?");
  EXPECT_STREQ(name_of(Colour::kBlue, kColours, "unknown"), "unknown");
  EXPECT_FALSE(value_of("blue", kColours).has_value());
  EXPECT_FALSE(value_of("", kColours).has_value());
  EXPECT_FALSE(value_of("Red", kColours).has_value());  // names are case-sensitive
}

// Both lookups are constexpr: a table can be checked at compile time.
static_assert(value_of(std::string_view("green"), kColours) == Colour::kGreen);
static_assert(std::string_view(name_of(Colour::kGreen, kColours)) == "green");

}  // namespace
}  // namespace pgmcl
