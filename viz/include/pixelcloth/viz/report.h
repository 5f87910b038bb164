#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pixelcloth::viz {

/// A report folder for people: timed steps, sections of text and pictures, written as report.json (every figure) and
/// index.html (the sections in order, then the timings).
class Report {
 public:
  /// Creates `folder` (or accepts an existing folder) for the report; nothing is written until write().
  explicit Report(const std::filesystem::path& folder);

  const std::filesystem::path& folder() const { return folder_; }
  /// folder() / `relative`, emptied of what an earlier run left there. The demo owns its report folder and remakes
  /// its datasets every run, so a dataset or model of an earlier run (other samples, other settings) would refuse to
  /// resume: each is made afresh in a folder from here.
  std::filesystem::path freshFolder(const std::filesystem::path& relative) const;
  /// The figures of report.json, by step: report.json()["body"] = {...}.
  nlohmann::json& json() { return json_; }

  /// Runs `work`, logging its start and end and recording its wall time under "steps".
  void step(const std::string& name, const std::function<void()>& work);
  /// A section of index.html: a title, a paragraph and pictures (paths relative to the folder).
  void section(const std::string& title, const std::string& text, const std::vector<std::string>& pictures);
  /// Writes report.json and index.html atomically, with the total time since construction.
  void write();

 private:
  std::filesystem::path folder_;
  nlohmann::json json_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace pixelcloth::viz
