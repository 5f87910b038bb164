#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "pixelcloth/cage/cage.h"

namespace pixelcloth::cage {

/// How long a cage curve is between two markers on a worn garment, learned from worn garments (DESIGN.md,
/// "Key-point-to-cage spline solver": the target of the spline's length term).
///
/// Worn cloth does not keep its pattern length at the scale of the markers. Along a curve it stretches where it is
/// pulled (5-15% near the armholes of the simulated T-shirts) and gathers into small wrinkles where it is pushed; a
/// smooth curve through the markers sees a wrinkled stretch as shorter than its rest length. What the markers show is
/// how far apart they are, so each curve gets a line, fitted by least squares on training garments,
///
///     worn length / rest length = intercept + slope x (chord / rest length),
///
/// where "worn length" is the segment's length after its wrinkles finer than the marker spacing are smoothed away
/// (LengthModelOptions::smoothingPasses). A line with slope 0 and intercept 1 is the pure length-preserving spline; 0
/// and 1 the other way round is a straight segment.
struct LengthModel {
  struct Line {
    double intercept = 1;
    double slope = 0;
    int segments = 0;  ///< training segments it was fitted on
    double rms = 0;    ///< root-mean-square error of the ratio on them
  };
  std::string garment;                 ///< Garment::name it was fitted for
  double markerSpacing = 0.1;          ///< MarkerOptions::spacing of the markers it was fitted with, metres
  int smoothingPasses = 2;             ///< LengthModelOptions::smoothingPasses used in fitting
  int samples = 0;                     ///< training garments
  std::map<std::string, Line> curves;  ///< per cage curve name

  /// Worn length of a segment of `curve` with rest length `rest` whose markers are `chord` apart, metres: the curve's
  /// line, but never shorter than the chord (a curve cannot be).
  double target(const std::string& curve, double rest, double chord) const;
  /// Throws InputError (prefixed with `context`) when the model is for another garment, lacks a curve of `cage` or
  /// holds a value that is not finite.
  void validate(const std::string& garmentName, const Cage& cage, const std::string& context) const;
};

/// How a LengthModel is fitted.
struct LengthModelOptions {
  /// Passes of the [1/4, 1/2, 1/4] filter over a training segment's vertices (its markers held) before its length is
  /// measured: wrinkles a few vertices wide go, the bend between the markers stays. 2 was best on the regularisation
  /// split of a 200-sample T-shirt dataset (0, 1, 2, 3, 5, 10 tried). In [0, 100].
  int smoothingPasses = 2;
  /// Each curve's line is pulled towards the line of all curves together with the weight of this many segments, so a
  /// curve with few training segments (a 12 cm shoulder seam has one per garment) gets a sensible line. >= 0.
  double shrinkage = 10;
  void validate() const;
};

nlohmann::json toJson(const LengthModel& model);
/// Parses the JSON form ({"format": "pixelcloth.length_model", "curves": {name: {"intercept", "slope", ...}}, ...});
/// throws InputError naming `context` and the field.
LengthModel lengthModelFromJson(const nlohmann::json& json, const std::string& context);
/// Reads a length model file (InputError naming the file when it is missing or malformed).
LengthModel readLengthModel(const std::filesystem::path& path);
/// Writes it atomically.
void writeLengthModel(const std::filesystem::path& path, const LengthModel& model);

}  // namespace pixelcloth::cage
