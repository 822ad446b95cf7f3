// Text that arrives from outside a process (a DDS sample's strings) made safe to print: a sample
// may carry terminal escape sequences, and nothing a peer writes may reach the user's terminal or
// a log as anything but visible characters.
#pragma once

#include <string>
#include <string_view>

namespace wsn::common {

/// `text` with every control character (bytes 0x00-0x1f except newline and tab, and 0x7f) written
/// as \xHH, and a backslash as \\, so that the result prints as what it is and can be read back.
/// Bytes 0x80 and above (UTF-8) pass unchanged.
std::string printable(std::string_view text);

}  // namespace wsn::common
