// LineEditor: turns the raw bytes a terminal (picocom, screen) or a program sends into command
// lines, and produces the echo the terminal expects from the remote end.
//
// Rules:
//   - a line ends at CR, LF or CRLF (CRLF counts once);
//   - backspace (0x08) and DEL (0x7F) erase the last character (echo "\b \b");
//   - Ctrl-C (0x03) and Ctrl-U (0x15) abandon the line being typed;
//   - ANSI escape sequences (arrow keys: ESC [ A ...) are skipped; TAB counts as a space;
//   - every other control byte and every byte >= 0x80 is dropped and counted (binary noise);
//   - a line longer than max_line bytes is discarded as a whole: the editor stops collecting
//     and echoing it and reports it as kOverlong once its end arrives.
// Memory is bounded by max_line whatever the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace stride::fw::console {

struct EditedLine {
  enum class Kind : std::uint8_t {
    kCommand,    ///< a complete line (possibly empty)
    kOverlong,   ///< a line longer than max_line ended; its text was discarded
    kCancelled,  ///< Ctrl-C / Ctrl-U abandoned the line
  };
  Kind kind = Kind::kCommand;
  std::string text;
};

class LineEditor {
 public:
  static constexpr std::size_t kDefaultMaxLine = 65536;

  explicit LineEditor(std::size_t max_line = kDefaultMaxLine, bool echo = true)
      : max_line_(max_line), echo_(echo) {}

  /// Consumes received bytes: appends complete lines to `lines` and the bytes to echo back to
  /// `echo` (nothing when echo is off).
  void feed(std::string_view bytes, std::vector<EditedLine>& lines, std::string& echo);

  /// Forgets the partial line and any escape sequence (after the link was reopened).
  void reset();

  std::size_t max_line() const noexcept { return max_line_; }
  /// Bytes dropped as noise since construction.
  std::uint64_t dropped_bytes() const noexcept { return dropped_; }
  /// The partial line typed so far.
  const std::string& pending() const noexcept { return buffer_; }

 private:
  enum class Escape : std::uint8_t { kNone, kEsc, kSequence };

  std::size_t max_line_;
  bool echo_;
  std::string buffer_;
  bool overflow_ = false;
  bool last_was_cr_ = false;
  Escape escape_ = Escape::kNone;
  std::uint64_t dropped_ = 0;
};

}  // namespace stride::fw::console
