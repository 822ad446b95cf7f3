// Negative control of the registration guard: Catch2 cases whose names ctest registration
// cannot carry. This binary is never registered with ctest; negative_control.py registers it
// the way catch_discover_tests does and expects check_registration.py to fail on it.
// The bad names are constants rather than literals in TEST_CASE so that the checks for accidental
// bad names in real tests (which look for such literals) see only these deliberate ones here.
#include <catch2/catch.hpp>

namespace {
constexpr const char* kUnbalancedBracket = "a name with an unbalanced [ bracket";
constexpr const char* kClosingBracket = "a name that ends the glue]";
constexpr const char* kSemicolon = "a name; split in two by the semicolon";
}  // namespace

TEST_CASE("a plain name, registered fine") { CHECK(true); }
TEST_CASE(kUnbalancedBracket) { CHECK(true); }
TEST_CASE("a name after the bracket, glued to it") { CHECK(true); }
TEST_CASE(kClosingBracket) { CHECK(true); }
TEST_CASE(kSemicolon) { CHECK(true); }
