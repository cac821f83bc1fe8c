// The SVG chart of a scaling study (`snee scale --plot`): speedup and parallel efficiency
// against the thread count, each beside its ideal line. Written by hand: two panels of lines,
// dots and labels need no plotting library.
#pragma once

#include <string>
#include <vector>

namespace snee {

struct ScalePoint {
  int threads = 0;
  double speedup = 0;
  double efficiency = 0;  // speedup / threads
};

std::string scale_plot_svg(const std::vector<ScalePoint>& points, const std::string& title,
                           const std::string& subtitle);

}  // namespace snee
