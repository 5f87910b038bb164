// motion::readMarkerTrajectories, the marker trajectories of reconstruct --markers-sequence: NPY when the first byte is
// even, CSV when odd (the rest but the second byte is the file); 1 to 8 markers by the second byte.
#include <cmath>
#include <fstream>

#include "fuzz_support.h"
#include "pixelcloth/motion/trajectories.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* out = pixelcloth::fuzz::seedOut()) {
    // Three frames of four markers, the third lost in the second frame, behind the selector bytes (4 markers: 3).
    pixelcloth::motion::MarkerTrajectories trajectories;
    for (int f = 0; f < 3; ++f) trajectories.frames.push_back(Eigen::MatrixX3d::Constant(4, 3, 0.1 * f));
    trajectories.frames[1].row(2).setConstant(std::nan(""));
    const std::filesystem::path folder(out), npy = folder / "plain.npy";
    pixelcloth::motion::writeMarkerTrajectories(npy, trajectories);
    std::ifstream in(npy, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(npy);
    std::ofstream(folder / "npy_4.bin", std::ios::binary) << std::string("\0\3", 2) << bytes;
    std::ofstream(folder / "csv_4.bin", std::ios::binary)
        << std::string("\1\3", 2) << "x0,y0,z0,x1,y1,z1,x2,y2,z2,x3,y3,z3\n0,0,0,0,0,0,0,0,0,0,0,0\n"
        << "0.1,0.1,0.1,0.1,0.1,0.1,,nan,,0.1,0.1,0.1\n0.2,0.2,0.2,0.2,0.2,0.2,0.2,0.2,0.2,0.2,0.2,0.2\n";
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const auto path = pixelcloth::fuzz::writeInput(data[0] % 2 ? "t.csv" : "t.npy", data + 2, size - 2);
  const int markers = 1 + data[1] % 8;
  return pixelcloth::fuzz::guarded([&] { pixelcloth::motion::readMarkerTrajectories(path, markers, "m.json"); });
}
