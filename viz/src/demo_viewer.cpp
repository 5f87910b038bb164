// The demo's 3D viewer section.
#include <map>
#include <sstream>

#include "pixelcloth/viz/demo.h"

namespace pixelcloth::viz {

void demoViewer(Report& report, const ViewSite& site) {
  std::map<std::string, int> groups;
  for (const ViewScene& scene : site.scenes) ++groups[scene.group];
  std::ostringstream text;
  text << "<a href='view/index.html'>view/index.html</a> shows " << site.scenes.size()
       << " scenes of this report in three.js, from this folder with no server: ";
  bool first = true;
  for (const auto& [group, count] : groups) {
    text << (first ? "" : ", ") << group << " " << count;
    first = false;
  }
  text << ". Turn each around, overlay ground truth or put it beside, colour the garment by its error (0 to 1 cm, "
          "as the error maps) or by patch, the cage curves by their normal jump, and play the sequences. The same "
          "page for any output folder: <code>pixelcloth view FOLDER</code>.";
  report.json()["viewer"] = {{"page", "view/index.html"}, {"scenes", site.scenes.size()}, {"groups", groups}};
  report.section("3D viewer", text.str(), {});
}

}  // namespace pixelcloth::viz
