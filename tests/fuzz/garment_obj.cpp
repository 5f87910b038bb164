// garment::importGarmentObj: a garment OBJ from another program, read without a cage file (UV islands, tube sleeves
// cut in two, seams, openings and their names, rescaled or mirrored UVs), behind core::readMesh's own checks.
#include "fuzz_support.h"
#include "pixelcloth/garment/garment.h"
#include "pixelcloth/garment/obj_import.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* out = pixelcloth::fuzz::seedOut()) {
    // The 100-vertex necktie as one island, and a 500-vertex T-shirt with tube sleeves (two UVs per underarm vertex).
    pixelcloth::garment::NecktieOptions tie;
    tie.targetVertices = 100;
    pixelcloth::garment::exportGarmentObj(pixelcloth::garment::makeNecktie(tie), std::filesystem::path(out) / "tie.obj");
    pixelcloth::garment::TShirtOptions shirt;
    shirt.targetVertices = 500;
    pixelcloth::garment::ObjExportOptions tubes;
    tubes.tubeSleeves = true;
    pixelcloth::garment::exportGarmentObj(pixelcloth::garment::makeTShirt(shirt),
                                          std::filesystem::path(out) / "tube_shirt.obj", tubes);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = pixelcloth::fuzz::writeInput("garment_obj/input.obj", data, size);
  return pixelcloth::fuzz::guarded([&] { pixelcloth::garment::importGarmentObj(path); });
}
