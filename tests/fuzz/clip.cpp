// motion::readClip through assimp, then the joint map and the retargeting: a BVH when the first byte is 0 mod 3, a
// glTF when 1, a Collada file when 2 (the rest is the file). Frames beyond the joint limits are clamped, so the
// retargeting runs on whatever the reader accepted.
#include "fuzz_support.h"
#include "pixelcloth/body/body.h"
#include "pixelcloth/motion/motion.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* names[] = {"clip.bvh", "clip.gltf", "clip.dae"};
  const auto path = pixelcloth::fuzz::writeInput(names[data[0] % 3], data + 1, size - 1);
  static const pixelcloth::body::Skeleton skeleton = pixelcloth::body::mannequinSkeleton();
  return pixelcloth::fuzz::guarded([&] {
    const pixelcloth::motion::Clip clip = pixelcloth::motion::readClip(path);
    pixelcloth::motion::retarget(clip, skeleton, pixelcloth::motion::detectJointMap(clip),
                                 pixelcloth::body::BeyondLimits::Clamp);
  });
}
