// Negative control of the registration guard: Catch2 cases whose names ctest registration
// cannot carry. This binary is never registered with ctest; negative_control.py registers it
// the way catch_discover_tests does and expects check_registration.py to fail on it.
#include <catch2/catch.hpp>

TEST_CASE("a plain name, registered fine") { CHECK(true); }
TEST_CASE("a name with an unbalanced [ bracket") { CHECK(true); }
TEST_CASE("a name after the bracket, glued to it") { CHECK(true); }
TEST_CASE("a name that ends the glue]") { CHECK(true); }
TEST_CASE("a name; split in two by the semicolon") { CHECK(true); }
