#include "progress_reporter.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace visgrab::app {

namespace {

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

constexpr int kBarWidth = 30;
constexpr std::size_t kDetailWidth = 45;

}  // namespace

std::string durationText(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  } else {
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  }
  return text;
}

ProgressReporter::ProgressReporter(std::string label, std::string unit, std::ostream& out,
                                   Settings settings)
    : label_(std::move(label)), unit_(std::move(unit)), out_(&out), settings_(std::move(settings)) {
  if (!settings_.clock) settings_.clock = steadySeconds;
  start_ = settings_.clock();
}

ProgressReporter::ProgressReporter(std::string label, std::string unit)
    : ProgressReporter(std::move(label), std::move(unit), std::cerr,
                       Settings{isatty(STDERR_FILENO) == 1, 5.0, {}}) {}

ProgressReporter::~ProgressReporter() { finish(); }

std::string ProgressReporter::line(long done, long total, std::string_view detail,
                                   double elapsed) const {
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  char counts[160];
  std::snprintf(counts, sizeof counts, "%ld/%ld %s", done, total, unit_.c_str());
  std::string text = label_ + ": ";
  if (settings_.terminal) {
    const long filled =
        total > 0 ? std::clamp(kBarWidth * done / total, 0L, long{kBarWidth}) : long{kBarWidth};
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kBarWidth, '.');
    text += "[" + bar + "] ";
  }
  text += counts;
  if (total > 0 && !settings_.terminal) {
    text += " (" + std::to_string(100 * done / total) + "%)";
  }
  char rateText[64];
  std::snprintf(rateText, sizeof rateText, "%.2f %s/s", rate, unit_.c_str());
  text += std::string(settings_.terminal ? "  " : ", ") + rateText;
  if (done < total && rate > 0.0) {
    text += std::string(settings_.terminal ? "  " : ", ") +
            durationText(static_cast<double>(total - done) / rate) + " left";
  } else if (done >= total) {
    text += std::string(settings_.terminal ? "  " : ", ") + "took " + durationText(elapsed);
  }
  if (!detail.empty()) {
    text += settings_.terminal ? "  " : ", ";
    text += detail.size() > kDetailWidth && settings_.terminal
                ? std::string(detail.substr(0, kDetailWidth))
                : std::string(detail);
  }
  return text;
}

void ProgressReporter::update(long done, long total, std::string_view detail) {
  const std::lock_guard lock(mutex_);
  const double now = settings_.clock();
  const bool last = done >= total;
  if (settings_.terminal) {
    // Back to the line start, the new text, and clear what a longer old text left.
    *out_ << "\r" << line(done, total, detail, now - start_) << "\x1b[K";
    open_ = true;
    if (last) {
      *out_ << "\n";
      open_ = false;
    }
    out_->flush();
    return;
  }
  const bool due = lastLine_ < 0.0 || now - lastLine_ >= settings_.interval;
  if ((last && done != lastDone_) || (!last && due)) {
    *out_ << line(done, total, detail, now - start_) << "\n";
    out_->flush();
    lastLine_ = now;
    lastDone_ = done;
  }
}

void ProgressReporter::finish() {
  const std::lock_guard lock(mutex_);
  if (open_) {
    *out_ << "\n";
    out_->flush();
    open_ = false;
  }
}

}  // namespace visgrab::app
