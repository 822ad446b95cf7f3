// Strings from DDS samples made safe to print: control characters escaped, the rest unchanged.
#include "common/printable.hpp"

#include <catch2/catch.hpp>
#include <string>

using wsn::common::printable;

TEST_CASE("printable text passes plain text, newlines, tabs and UTF-8 unchanged", "[printable]") {
  CHECK(printable("supernode 2: stalled at tick 40") == "supernode 2: stalled at tick 40");
  CHECK(printable("two\nlines\tand a tab") == "two\nlines\tand a tab");
  CHECK(printable("\xce\xb5K 0.18") == "\xce\xb5K 0.18");  // εK
  CHECK(printable("").empty());
}

TEST_CASE("printable text escapes terminal escape sequences and other control characters", "[printable]") {
  CHECK(printable("\x1b[31mFAILED\x1b[0m") == "\\x1b[31mFAILED\\x1b[0m");
  CHECK(printable("carriage\rreturn") == "carriage\\x0dreturn");
  CHECK(printable(std::string("nul\0byte", 8)) == "nul\\x00byte");
  CHECK(printable("bell\a and delete\x7f") == "bell\\x07 and delete\\x7f");
}

TEST_CASE("printable text escapes backslashes so that an escape in the input cannot pass for one", "[printable]") {
  CHECK(printable("C:\\x1b") == "C:\\\\x1b");
  CHECK(printable("\\\x1b") == "\\\\\\x1b");
}
