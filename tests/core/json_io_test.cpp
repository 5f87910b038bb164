// JSON files: atomic round trip, syntax errors located by line and column, and the required-field helpers' messages.
#include "pixelcloth/core/json_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "support/test_util.h"

namespace pc = pixelcloth::core;
namespace fs = std::filesystem;
using nlohmann::json;

TEST(JsonIo, RoundTripKeepsEveryValue) {
  fs::path dir = pixelcloth::testing::freshDir("roundtrip");
  json manifest = {{"garment", "tshirt"}, {"counts", {{"train", 900}, {"test", 100}}},     {"seed", 12345678901234LL},
                   {"scale", 0.1},        {"splits", {"train", "regularisation", "test"}}, {"name", "caf\u00e9"},
                   {"empty", nullptr}};
  pc::writeJson(dir / "manifest.json", manifest);
  EXPECT_EQ(pc::readJson(dir / "manifest.json"), manifest);
  std::string text = pc::readTextFile(dir / "manifest.json");
  EXPECT_NE(text.find("\n  \"counts\""), std::string::npos);  // two-space indent by default
  EXPECT_EQ(text.back(), '\n');
  pc::writeJson(dir / "compact.json", manifest, -1);
  std::string compact = pc::readTextFile(dir / "compact.json");
  EXPECT_EQ(std::count(compact.begin(), compact.end(), '\n'), 1);
  EXPECT_EQ(pc::readJson(dir / "compact.json"), manifest);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);  // no temporary left
}

TEST(JsonIo, SyntaxErrorsGiveFileLineAndColumn) {
  fs::path dir = pixelcloth::testing::freshDir("syntax");
  std::ofstream(dir / "bad.json") << "{\n  \"a\": 1,\n  \"b\": tru\n}\n";
  std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readJson(dir / "bad.json"); });
  EXPECT_EQ(message.rfind((dir / "bad.json").string() + ": invalid JSON at line 3, column ", 0), 0u) << message;
  std::ofstream(dir / "cut.json") << "{\"a\": [1, 2";
  message = pixelcloth::testing::inputErrorOf([&] { pc::readJson(dir / "cut.json"); });
  EXPECT_EQ(message.rfind((dir / "cut.json").string() + ": invalid JSON at line 1, column 12 (byte 12)", 0), 0u)
      << message;
  std::ofstream(dir / "empty.json") << "";
  message = pixelcloth::testing::inputErrorOf([&] { pc::readJson(dir / "empty.json"); });
  EXPECT_EQ(message.rfind((dir / "empty.json").string() + ": invalid JSON at line 1", 0), 0u) << message;
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::readJson(dir / "absent.json"); }),
            (dir / "absent.json").string() + ": no such file");
}

TEST(JsonIo, AFileOfMoreThan256MbIsRefusedBeforeItIsRead) {
  const fs::path dir = pixelcloth::testing::freshDir("huge");
  { std::ofstream(dir / "poses.json") << "["; }
  fs::resize_file(dir / "poses.json", (256u << 20) + 1);  // sparse: no disk is used
  const std::string message = pixelcloth::testing::inputErrorOf([&] { pc::readJson(dir / "poses.json"); });
  EXPECT_EQ(message, (dir / "poses.json").string() +
                         ": 268435457 bytes, more than the 256 MB a JSON file pixelcloth reads may hold");
}

TEST(JsonIo, DeepNestingIsRefusedBeforeParsingAndBracketsInStringsDoNotCount) {
  // 150,000 levels under a key: nlohmann parses it, then overflows the stack copying it. Refused before parsing.
  const std::string bomb = "{\"settings\": " + std::string(150000, '[') + std::string(150000, ']') + "}";
  const std::string message = pixelcloth::testing::inputErrorOf([&] { pc::parseJson(bomb, "manifest.json"); });
  EXPECT_EQ(message, "manifest.json: JSON nested more than 64 levels deep (byte 77)") << message;
  // 64 levels are fine, and brackets inside strings (escaped quotes too) are text.
  const std::string deep = std::string(63, '[') + "{\"a\":\"[[[\\\"{{{\"}" + std::string(63, ']');
  EXPECT_EQ(pc::parseJson(deep, "deep.json").dump(), deep);
}

TEST(JsonIo, RequiredFieldsSayWhatIsMissingOrWrong) {
  json manifest = {{"seed", 7}, {"garment", "tshirt"}, {"scale", 0.5}, {"splits", {1, 2}}};
  EXPECT_EQ(pc::requireField(manifest, "garment", "manifest.json"), "tshirt");
  EXPECT_EQ(pc::requireValue<int>(manifest, "seed", "manifest.json"), 7);
  EXPECT_EQ(pc::requireValue<double>(manifest, "seed", "manifest.json"), 7.0);  // an integer is a number
  EXPECT_EQ(pc::requireValue<std::string>(manifest, "garment", "manifest.json"), "tshirt");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::requireField(manifest, "body", "manifest.json"); }),
            "manifest.json: missing field 'body'");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::requireValue<int>(manifest, "garment", "manifest.json"); }),
            "manifest.json: field 'garment' is a string \"tshirt\", expected an integer");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::requireValue<int>(manifest, "scale", "manifest.json"); }),
            "manifest.json: field 'scale' is number 0.5, expected an integer");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::requireValue<double>(manifest, "garment", "manifest.json"); }),
            "manifest.json: field 'garment' is string, expected a number");
  EXPECT_EQ(
      pixelcloth::testing::inputErrorOf([&] { pc::requireValue<std::string>(manifest, "splits", "manifest.json"); }),
      "manifest.json: field 'splits' is array, expected a string");
  EXPECT_EQ(pixelcloth::testing::inputErrorOf(
                [&] { pc::requireField(manifest["splits"], "train", "manifest.json: splits"); }),
            "manifest.json: splits: expected a JSON object, found array");
}

// Found reading the readers for the fuzz targets (docs/reliability.md): nlohmann's get<int> wraps an out-of-range
// integer modulo 2^32, so "rows": 4294967300 was read as 4 and "crc32": -1 as 4294967295.
TEST(JsonIo, IntegersOutOfTheTypesRangeAreRefusedNotWrapped) {
  const json j = json::parse(R"({"rows": 4294967300, "crc32": -1, "big": 18446744073709551615, "ok": 7,
                                 "list": [1, 4294967297]})");
  auto refusal = [&](const std::function<void()>& read) { return pixelcloth::testing::inputErrorOf(read); };
  const std::string rows = refusal([&] { pc::requireValue<int>(j, "rows", "manifest.json"); });
  EXPECT_NE(rows.find("manifest.json: field 'rows' is 4294967300, out of the range"), std::string::npos) << rows;
  EXPECT_NE(refusal([&] { pc::requireValue<std::uint32_t>(j, "crc32", "m.json"); }).find("'crc32'"), std::string::npos);
  EXPECT_NE(refusal([&] { pc::requireValue<std::int64_t>(j, "big", "m.json"); }).find("'big'"), std::string::npos);
  EXPECT_NE(refusal([&] { pc::requireValue<std::vector<int>>(j, "list", "m.json"); }).find("entry 1"), std::string::npos);
  EXPECT_EQ(pc::requireValue<std::uint64_t>(j, "big", "m.json"), 18446744073709551615ULL);
  EXPECT_EQ(pc::requireValue<int>(j, "ok", "m.json"), 7);
  EXPECT_EQ(pc::requireValue<std::uint32_t>(j, "ok", "m.json"), 7u);
}

// nlohmann's json.value(key, fallback) throws its type_error, naming no file, when the key holds another type; the
// readers of model.json, pca.json and base manifests used it (fuzzing found the model.json case).
TEST(JsonIo, ValueOrFallsBackOnlyWhenTheKeyIsAbsent) {
  const nlohmann::json object = {{"format", 5}, {"width", 0.5}};
  EXPECT_EQ(pc::valueOr(object, "width", 1.0, "m.json"), 0.5);
  EXPECT_EQ(pc::valueOr(object, "absent", 1.0, "m.json"), 1.0);
  EXPECT_EQ(pc::valueOr(nlohmann::json::array(), "width", 1.0, "m.json"), 1.0);
  EXPECT_EQ(pixelcloth::testing::inputErrorOf([&] { pc::valueOr<std::string>(object, "format", "", "m.json"); }),
            "m.json: field 'format' is number, expected a string");
}
