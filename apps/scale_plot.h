// The SVG chart of a scaling study (`snee scale --plot`): speedup and parallel efficiency
// against the thread count, each beside its ideal line, and the efficiency by CPU time, which a
// busy shared machine does not distort. Written by hand: two panels of lines, dots and labels
// need no plotting library.
#pragma once

#include <string>
#include <vector>

namespace snee {

struct ScalePoint {
  int threads = 0;
  double speedup = 0;
  double efficiency = 0;       // speedup / threads
  double work_efficiency = 0;  // CPU time at the base thread count / CPU time at this one
};

std::string scale_plot_svg(const std::vector<ScalePoint>& points, const std::string& title,
                           const std::string& subtitle);

}  // namespace snee
