#include "cli_options.h"

#include <algorithm>
#include <cstdio>

namespace contour_reg::cli {

void printReadReport(const io::ScanLog &log) {
  for (const std::string &problem : log.report.problems) std::fprintf(stderr, "warning: %s\n", problem.c_str());
  if (log.report.skipped > log.report.problems.size())
    std::fprintf(stderr, "warning: %s: %zu bad lines skipped in all\n", log.source.c_str(), log.report.skipped);
  if (log.report.reordered > 0)
    std::fprintf(stderr, "note: %s: %zu scans were out of stamp order and were sorted\n", log.source.c_str(),
                 log.report.reordered);
}

}  // namespace contour_reg::cli

#include <unistd.h>

namespace contour_reg::cli {

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() {
  if (enabled_ && shown_ >= 0) std::fprintf(stderr, "\n");
}

void ProgressBar::operator()(std::size_t done, std::size_t total) {
  if (!enabled_ || total == 0) return;
  const int percent = static_cast<int>(100 * done / total);
  if (percent == shown_) return;
  shown_ = percent;
  const int width = 30, filled = percent * width / 100;
  std::fprintf(stderr, "\r%s [%s%s] %3d%%", label_.c_str(), std::string(std::size_t(filled), '#').c_str(),
               std::string(std::size_t(width - filled), ' ').c_str(), percent);
  std::fflush(stderr);
}

}  // namespace contour_reg::cli
