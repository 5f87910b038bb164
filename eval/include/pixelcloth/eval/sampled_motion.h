#pragma once

// A motion of pixelcloth's own, for the demo and the bench: key poses from the paper's pose sampler (its appendix),
// eased into each other, with root motion. Written as a GLB (motion::writeAnimatedGlb), it is a clip like any other.

#include <cstdint>

#include "pixelcloth/body/body.h"
#include "pixelcloth/motion/glb.h"

namespace pixelcloth::eval {

/// `keys` key poses drawn by sim::PoseSampler with `seed` (arms clear of the torso), each eased into the next over
/// `framesPerKey` frames (smoothstep on the Euler angles, which stays inside the joint limits' box) and the last back
/// into the first: keys x framesPerKey + 1 frames at `fps`, the root turning 40 degrees about the vertical and stepping
/// 0.3 m forward over the clip. The scene's body is `body`, which must outlive it.
motion::AnimatedScene sampledMotion(const body::Body& body, int keys, int framesPerKey, double fps, std::uint64_t seed);

}  // namespace pixelcloth::eval
