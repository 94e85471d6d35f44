// The progress reporter with an injected clock: plain lines (no '\r') at most every interval,
// the first and the last always; a live line on a terminal.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "progress_reporter.hpp"

namespace {

using visgrab::app::ProgressReporter;

// A clock the test sets.
struct ManualClock {
  double now = 0.0;
  ProgressReporter::Clock clock() {
    return [this] { return now; };
  }
};

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ProgressReporter, PlainLinesAreRateLimitedAndCarryNoCarriageReturn) {
  ManualClock t;
  std::ostringstream out;
  {
    ProgressReporter r("run", "trials", out, {false, 5.0, t.clock()});
    t.now = 1.0;
    r.update(1, 10, "scenes 1/2");  // first: written
    t.now = 2.0;
    r.update(2, 10);  // 1 s later: not
    t.now = 5.9;
    r.update(3, 10);  // 4.9 s after the first line: not
    t.now = 6.0;
    r.update(4, 10, "scenes 1/2");  // 5 s: written
    t.now = 7.0;
    r.update(5, 10);
    t.now = 9.0;
    r.update(10, 10, "scenes 2/2");  // the last: written at once
    r.update(10, 10, "scenes 2/2");  // and once only
  }
  const std::string text = out.str();
  EXPECT_EQ(text.find('\r'), std::string::npos);
  EXPECT_EQ(text.find('\x1b'), std::string::npos);
  const auto lines = linesOf(text);
  ASSERT_EQ(lines.size(), 3u) << text;
  // 1 trial in 1 s; 4 trials in 6 s: 6 left at 0.67/s = 9 s; done after 9 s.
  EXPECT_EQ(lines[0], "run: 1/10 trials (10%), 1.00 trials/s, 0m09s left, scenes 1/2");
  EXPECT_EQ(lines[1], "run: 4/10 trials (40%), 0.67 trials/s, 0m09s left, scenes 1/2");
  EXPECT_EQ(lines[2], "run: 10/10 trials (100%), 1.11 trials/s, took 0m09s, scenes 2/2");
  EXPECT_EQ(text.back(), '\n');
}

TEST(ProgressReporter, ALongJobWritesALineEveryInterval) {
  ManualClock t;
  std::ostringstream out;
  ProgressReporter r("db generate", "scenes", out, {false, 5.0, t.clock()});
  for (int i = 1; i <= 60; ++i) {
    t.now = i;  // one scene a second for a minute
    r.update(i, 100);
  }
  // t = 1, 6, 11, ..., 56: 12 lines.
  EXPECT_EQ(linesOf(out.str()).size(), 12u) << out.str();
}

TEST(ProgressReporter, OnATerminalOneLineIsRedrawnAndEndedWhenDone) {
  ManualClock t;
  std::ostringstream out;
  ProgressReporter r("baseline", "scenes", out, {true, 5.0, t.clock()});
  t.now = 1.0;
  r.update(1, 4, "plain/single/cocacola/01");
  t.now = 1.1;
  r.update(2, 4);  // a live line is redrawn every time
  EXPECT_EQ(out.str().find('\n'), std::string::npos);
  t.now = 2.0;
  r.update(4, 4);
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 3);
  EXPECT_EQ(text.back(), '\n');
  EXPECT_NE(text.find("baseline: [###############...............] 2/4 scenes"), std::string::npos)
      << text;
  EXPECT_NE(text.find("\x1b[K"), std::string::npos);
}

TEST(ProgressReporter, AnUnfinishedLiveLineIsEndedAtTheEnd) {
  ManualClock t;
  std::ostringstream out;
  {
    ProgressReporter r("report pictures", "pictures", out, {true, 5.0, t.clock()});
    r.update(1, 3);
  }
  EXPECT_EQ(out.str().back(), '\n');
}

TEST(ProgressReporter, DurationText) {
  EXPECT_EQ(visgrab::app::durationText(0.4), "0m00s");
  EXPECT_EQ(visgrab::app::durationText(65), "1m05s");
  EXPECT_EQ(visgrab::app::durationText(3725), "1h02m");
}

}  // namespace
