// Console line editor: echo, backspace/DEL, CR/LF/CRLF, Ctrl-C, escape sequences, binary
// noise and overlong lines.
#include "stride/firmware/console/line_editor.hpp"

#include <random>

#include <gtest/gtest.h>

namespace stride::fw::console {
namespace {

struct Fed {
  std::vector<EditedLine> lines;
  std::string echo;
};

Fed feed(LineEditor& editor, std::string_view bytes) {
  Fed out;
  editor.feed(bytes, out.lines, out.echo);
  return out;
}

TEST(ConsoleLineEditor, EchoesAndEndsLinesAtCrLfOrCrLf) {
  LineEditor editor;
  Fed f = feed(editor, "get a\rget b\nget c\r\nget d\n\r");
  ASSERT_EQ(f.lines.size(), 5u);  // LF CR is two line ends (an empty line), CR LF only one
  EXPECT_EQ(f.lines[0].text, "get a");
  EXPECT_EQ(f.lines[1].text, "get b");
  EXPECT_EQ(f.lines[2].text, "get c");
  EXPECT_EQ(f.lines[3].text, "get d");
  EXPECT_EQ(f.lines[4].text, "");
  EXPECT_EQ(f.echo, "get a\r\nget b\r\nget c\r\nget d\r\n\r\n");
}

TEST(ConsoleLineEditor, CrLfSplitAcrossReads) {
  LineEditor editor;
  Fed a = feed(editor, "status\r");
  Fed b = feed(editor, "\nhelp\r");
  ASSERT_EQ(a.lines.size(), 1u);
  ASSERT_EQ(b.lines.size(), 1u);
  EXPECT_EQ(b.lines[0].text, "help");
}

TEST(ConsoleLineEditor, BackspaceAndDeleteErase) {
  LineEditor editor;
  Fed f = feed(editor, "gex\x08t\x7f\x7ft a\r");
  ASSERT_EQ(f.lines.size(), 1u);
  EXPECT_EQ(f.lines[0].text, "gt a");
  EXPECT_EQ(f.echo, "gex\b \bt\b \b\b \bt a\r\n");
  // Backspace on an empty line does nothing.
  Fed g = feed(editor, "\x08\x7fok\n");
  EXPECT_EQ(g.lines[0].text, "ok");
  EXPECT_EQ(g.echo, "ok\r\n");
}

TEST(ConsoleLineEditor, CtrlCAbandonsTheLine) {
  LineEditor editor;
  Fed f = feed(editor, "set walk.step_time 9\x03get x\r");
  ASSERT_EQ(f.lines.size(), 2u);
  EXPECT_EQ(f.lines[0].kind, EditedLine::Kind::kCancelled);
  EXPECT_EQ(f.lines[1].text, "get x");
}

TEST(ConsoleLineEditor, SkipsEscapeSequencesAndDropsNoise) {
  LineEditor editor;
  Fed f = feed(editor, std::string("\x1b[Ahe\x1b[1;5Dl\x01\x02\xff\x80p\tx\x00\r", 21));
  ASSERT_EQ(f.lines.size(), 1u);
  EXPECT_EQ(f.lines[0].text, "help x");
  EXPECT_EQ(editor.dropped_bytes(), 5u);
  EXPECT_EQ(f.echo, "help x\r\n");
}

TEST(ConsoleLineEditor, OverlongLineIsDiscardedWhole) {
  LineEditor editor(16);
  Fed f = feed(editor, std::string(40, 'x') + "\rget a\r");
  ASSERT_EQ(f.lines.size(), 2u);
  EXPECT_EQ(f.lines[0].kind, EditedLine::Kind::kOverlong);
  EXPECT_TRUE(f.lines[0].text.empty());
  EXPECT_EQ(f.lines[1].kind, EditedLine::Kind::kCommand);
  EXPECT_EQ(f.lines[1].text, "get a");
  // Exactly max_line characters is still a line.
  Fed g = feed(editor, std::string(16, 'y') + "\n");
  EXPECT_EQ(g.lines[0].kind, EditedLine::Kind::kCommand);
  EXPECT_EQ(g.lines[0].text.size(), 16u);
}

TEST(ConsoleLineEditor, NoEchoWhenOff) {
  LineEditor editor(100, false);
  Fed f = feed(editor, "abc\x08\r");
  EXPECT_EQ(f.lines[0].text, "ab");
  EXPECT_TRUE(f.echo.empty());
}

TEST(ConsoleLineEditor, RandomBytesKeepMemoryBoundedAndRecover) {
  LineEditor editor(64);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string noise(200000, '\0');
  for (char& c : noise) c = static_cast<char>(byte(rng));
  Fed f = feed(editor, noise);
  for (const auto& line : f.lines) EXPECT_LE(line.text.size(), 64u);
  EXPECT_LE(editor.pending().size(), 64u);
  // After noise, Ctrl-C and a clean line parse normally.
  Fed g = feed(editor, "\x03status\r");
  ASSERT_FALSE(g.lines.empty());
  EXPECT_EQ(g.lines.back().text, "status");
}

}  // namespace
}  // namespace stride::fw::console
