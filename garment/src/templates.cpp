// The built-in garment templates, chosen by name in one place.
#include <string>
#include <vector>

#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::garment {

const std::vector<std::string>& templateNames() {
  static const std::vector<std::string> names = {"tshirt", "necktie"};
  return names;
}

Garment makeGarment(const std::string& name, const std::string& context) {
  if (name == "tshirt") return makeTShirt();
  if (name == "necktie") return makeNecktie();
  std::string known;
  for (const std::string& n : templateNames()) known += (known.empty() ? "" : ", ") + n;
  PIXELCLOTH_FAIL(context << ": unknown garment template '" << name << "'; expected one of: " << known);
}

int poseSizeOf(const std::string& garmentName) {
  return garmentName == "necktie" ? body::kNecktiePoseSize : body::kPoseSize;
}

}  // namespace pixelcloth::garment
