// Garment folders: what saveGarment writes, and garment import (OBJ with UVs plus the cage's polylines).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/mesh_io.h"
#include "pixelcloth/garment/garment.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
namespace pc = pixelcloth::core;
namespace pg = pixelcloth::garment;

TEST(GarmentFolder, ObjKeepsUvsAndJsonDescribesSeams) {
  fs::path dir = pixelcloth::testing::freshDir("garment");
  pg::Garment shirt = pg::makeTShirt();
  pg::saveGarment(dir, shirt);
  pc::Mesh mesh = pc::readMesh(dir / "garment.obj");
  EXPECT_EQ(mesh.F, shirt.mesh.F);
  ASSERT_TRUE(mesh.hasUV());
  for (int f = 0; f < mesh.numFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_LT((mesh.UV.row(mesh.FUV(f, k)) - shirt.mesh.UV.row(shirt.mesh.FUV(f, k))).norm(), 1e-6);
  nlohmann::json json = pc::readJson(dir / "garment.json");
  EXPECT_EQ(json["seams"].size(), shirt.seams.size());
  EXPECT_EQ(json["face_panel"].size(), static_cast<size_t>(mesh.numFaces()));
  EXPECT_EQ(json["layouts"][0]["name"], "front");
}

