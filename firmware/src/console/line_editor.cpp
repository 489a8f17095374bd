// LineEditor implementation (see the header for the rules).
#include "stride/firmware/console/line_editor.hpp"

namespace stride::fw::console {

void LineEditor::reset() {
  buffer_.clear();
  overflow_ = false;
  last_was_cr_ = false;
  escape_ = Escape::kNone;
}

void LineEditor::feed(std::string_view bytes, std::vector<EditedLine>& lines, std::string& echo) {
  for (const char ch : bytes) {
    const auto c = static_cast<unsigned char>(ch);
    // Escape sequences: ESC, then '[' or 'O', then parameters up to a final byte 0x40..0x7E.
    if (escape_ == Escape::kEsc) {
      escape_ = (c == '[' || c == 'O') ? Escape::kSequence : Escape::kNone;
      continue;
    }
    if (escape_ == Escape::kSequence) {
      if (c >= 0x40 && c <= 0x7E) escape_ = Escape::kNone;
      if (c < 0x20 || c > 0x7E) escape_ = Escape::kNone;  // broken sequence: drop it
      continue;
    }
    if (c == '\n' && last_was_cr_) {  // CRLF ends one line, not two
      last_was_cr_ = false;
      continue;
    }
    last_was_cr_ = false;

    if (c == '\r' || c == '\n') {
      last_was_cr_ = c == '\r';
      EditedLine line;
      if (overflow_) {
        line.kind = EditedLine::Kind::kOverlong;
      } else {
        line.text = buffer_;
      }
      lines.push_back(std::move(line));
      buffer_.clear();
      overflow_ = false;
      if (echo_) echo += "\r\n";
    } else if (c == 0x08 || c == 0x7F) {
      if (!overflow_ && !buffer_.empty()) {
        buffer_.pop_back();
        if (echo_) echo += "\b \b";
      }
    } else if (c == 0x03 || c == 0x15) {
      lines.push_back({EditedLine::Kind::kCancelled, {}});
      buffer_.clear();
      overflow_ = false;
      if (echo_) echo += "^C\r\n";
    } else if (c == 0x1B) {
      escape_ = Escape::kEsc;
    } else if (c == '\t' || (c >= 0x20 && c < 0x7F)) {
      if (overflow_) continue;
      if (buffer_.size() >= max_line_) {
        overflow_ = true;
        buffer_.clear();
        buffer_.shrink_to_fit();
        continue;
      }
      const char printable = c == '\t' ? ' ' : static_cast<char>(c);
      buffer_.push_back(printable);
      if (echo_) echo.push_back(printable);
    } else {
      ++dropped_;  // other control bytes and 8-bit bytes: binary noise
    }
  }
}

}  // namespace stride::fw::console
