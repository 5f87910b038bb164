#include "pixelcloth/viz/report.h"

#include <sstream>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/progress.h"

namespace pixelcloth::viz {

using namespace core;

namespace {
void writeIndex(const std::filesystem::path& out, const nlohmann::json& report) {
  std::ostringstream html;
  html << "<!doctype html><html><head><meta charset='utf-8'><title>pixelcloth demo</title>"
       << "<style>body{font-family:sans-serif;max-width:1400px;margin:2em auto;color:#222}img{max-width:100%;"
       << "border:1px solid #ddd}td,th{padding:2px 10px;text-align:left}</style></head><body>"
       << "<h1>pixelcloth demo report</h1><p>Everything the toolkit does so far, on the built-in mannequin and "
       << "garments. Numbers are in <code>report.json</code>.</p>";
  if (report.contains("viewer"))
    html << "<p><b><a href='" << report["viewer"]["page"].get<std::string>()
         << "'>Open the 3D viewer</a></b>: " << report["viewer"]["scenes"].get<int>()
         << " scenes of this report (garments on their bodies, learned predictions against ground truth, "
            "reconstructions with their markers, sequences) to turn around in the browser.</p>";
  for (const auto& section : report["sections"]) {
    html << "<h2>" << section["title"].get<std::string>() << "</h2><p>" << section["text"].get<std::string>() << "</p>";
    for (const auto& picture : section["pictures"]) html << "<p><img src='" << picture.get<std::string>() << "'></p>";
  }
  html << "<h2>Timings</h2><table><tr><th>step</th><th>seconds</th></tr>";
  for (const auto& step : report["steps"])
    html << "<tr><td>" << step["name"].get<std::string>() << "</td><td>" << step["seconds"].get<double>()
         << "</td></tr>";
  html << "</table></body></html>\n";
  writeTextAtomically(out / "index.html", html.str());
}
}  // namespace

Report::Report(const std::filesystem::path& folder)
    : folder_(folder),
      json_({{"format", "pixelcloth.demo"},
             {"version", 1},
             {"steps", nlohmann::json::array()},
             {"sections", nlohmann::json::array()}}),
      start_(std::chrono::steady_clock::now()) {
  ensureOutputFolder(folder_);
}

std::filesystem::path Report::freshFolder(const std::filesystem::path& relative) const {
  const std::filesystem::path path = folder_ / relative;
  std::filesystem::remove_all(path);
  return path;
}

void Report::step(const std::string& name, const std::function<void()>& work) {
  PIXELCLOTH_INFO("demo: " << name << " ...");
  const auto start = std::chrono::steady_clock::now();
  work();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  json_["steps"].push_back({{"name", name}, {"seconds", seconds}});
  PIXELCLOTH_INFO("demo: " << name << " done in " << formatDuration(seconds) << " (" << seconds << " s)");
}

void Report::section(const std::string& title, const std::string& text, const std::vector<std::string>& pictures) {
  json_["sections"].push_back({{"title", title}, {"text", text}, {"pictures", pictures}});
}

void Report::write() {
  json_["total_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  writeJson(folder_ / "report.json", json_);
  writeIndex(folder_, json_);
  PIXELCLOTH_INFO("demo: report written to " << (folder_ / "index.html").string() << " in "
                                             << formatDuration(json_["total_seconds"].get<double>()));
}

}  // namespace pixelcloth::viz
