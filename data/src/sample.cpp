#include "pixelcloth/data/sample.h"

namespace pixelcloth::data {

const char* rejectionName(Rejection rejection) {
  switch (rejection) {
    case Rejection::None:
      return "none";
    case Rejection::TriangleShrank:
      return "triangle_shrank";
    case Rejection::TriangleGrew:
      return "triangle_grew";
    case Rejection::NotFinite:
      return "not_finite";
    case Rejection::ArmInsideTorso:
      return "arm_inside_torso";
    case Rejection::Penetrated:
      return "penetrated";
  }
  return "unknown";
}

}  // namespace pixelcloth::data
