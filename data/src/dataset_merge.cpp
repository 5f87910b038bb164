// Merging shard folders into one dataset, streamed in index order.
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "dataset_internal.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/core/run_folder.h"
#include "pixelcloth/data/dataset.h"

namespace pixelcloth::data {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace detail;

DatasetInfo mergeDatasets(const std::vector<fs::path>& shardFolders, const fs::path& out) {
  PIXELCLOTH_CHECK(!shardFolders.empty(), "dataset merge: no shard folders given");
  std::vector<DatasetInfo> shards;
  for (const fs::path& folder : shardFolders) shards.push_back(readDatasetInfo(folder));
  std::sort(shards.begin(), shards.end(),
            [](const DatasetInfo& a, const DatasetInfo& b) { return a.settings.first() < b.settings.first(); });
  const DatasetInfo& reference = shards.front();
  const DatasetSettings& s = reference.settings;
  for (const DatasetInfo& shard : shards) {
    const std::string differs = shard.settings.firstDifference(s, /*ignoreShard=*/true);
    PIXELCLOTH_CHECK(differs.empty(), (shard.folder / kManifest).string()
                                          << ": '" << differs << "' is " << shard.settings.toJson()[differs].dump()
                                          << ", but " << (reference.folder / kManifest).string() << " has "
                                          << s.toJson()[differs].dump() << "; shards of one dataset must agree");
  }
  // Coverage of [0, N): sorted by first index, each shard must start where the previous ended.
  int next = 0;
  for (const DatasetInfo& shard : shards) {
    const int first = shard.settings.first(), end = shard.settings.end();
    PIXELCLOTH_CHECK(first <= next, "dataset merge: samples [" << next << ", " << first << ") are in no shard (next "
                                                               << "shard: " << shard.folder.string() << ", shard "
                                                               << shard.settings.shard.toString() << ")");
    PIXELCLOTH_CHECK(first >= next, "dataset merge: " << shard.folder.string() << " (shard "
                                                      << shard.settings.shard.toString() << ", samples [" << first
                                                      << ", " << end << ")) overlaps samples before " << next);
    next = end;
  }
  PIXELCLOTH_CHECK(next == s.count, "dataset merge: samples [" << next << ", " << s.count
                                                               << ") are in no shard; every shard of the " << s.count
                                                               << "-sample dataset must be given");
  // The same body, garment and dressing in every shard.
  for (const DatasetInfo& shard : shards) {
    for (const std::string& file : sharedFiles(reference.folder)) {
      if (!byteComparable(file)) continue;
      PIXELCLOTH_CHECK(sameBytes(reference.folder / file, shard.folder / file),
                       (shard.folder / file).string() << " differs from " << (reference.folder / file).string()
                                                      << ": the shards were made with different bodies, garments or "
                                                      << "dressings");
    }
  }

  // Output folder: new or empty.
  core::checkOutputFolder(out);
  core::checkRunFolder(out, {"", {}, "a merged dataset"});
  std::error_code ec;
  if (fs::is_directory(out, ec))
    PIXELCLOTH_CHECK(fs::directory_iterator(out) == fs::directory_iterator(),
                     out.string() << ": is not empty; merge writes into a new or empty folder");
  for (const DatasetInfo& shard : shards)
    PIXELCLOTH_CHECK(!fs::equivalent(shard.folder, out, ec), out.string() << ": is one of the shards");

  // Everything is written into a staging folder beside `out`, renamed into place at the end: a failed merge (a
  // damaged shard, a full disk) leaves no half-filled folder to block the retry.
  fs::path target = fs::absolute(out).lexically_normal();
  if (target.filename().empty()) target = target.parent_path();  // "merged/"
  const fs::path staging =
      target.parent_path() / (target.filename().string() + ".merging-" + std::to_string(::getpid()));
  fs::remove_all(staging, ec);
  fs::create_directories(staging);
  struct RemoveUnlessDone {
    fs::path folder;
    bool done = false;
    ~RemoveUnlessDone() {
      std::error_code ignored;
      if (!done) fs::remove_all(folder, ignored);
    }
  } cleanup{staging};
  json checksums = json::object();
  for (const std::string& file : sharedFiles(reference.folder)) {
    core::writeAtomically(staging / file, [&](const fs::path& temporary) {
      fs::copy_file(reference.folder / file, temporary, fs::copy_options::overwrite_existing);
    });
    checksums[file] = reference.manifest["checksums"].value(
        file, json{{"crc32", fileCrc32(staging / file)}, {"bytes", fs::file_size(staging / file)}});
  }

  // Arrays: each shard's rows appended in order; each input's CRC checked against its manifest on the way.
  const std::int64_t N = s.count, V = s.vertexCount;
  struct Part {
    const char* file;
    std::string dtype;
    std::vector<std::int64_t> shape;
  };
  const std::vector<Part> parts = {{kPoses, "<f4", {N, s.poseSize}},
                                   {kPositions, "<f4", {N, V, 3}},
                                   {kOffsets, "<f4", {N, V, 3}},
                                   {kSplit, "|u1", {N}}};
  core::Progress progress("dataset merge", static_cast<std::int64_t>(parts.size() * shards.size()));
  std::vector<char> buffer(1 << 20);
  for (const Part& part : parts) {
    core::writeAtomically(staging / part.file, [&](const fs::path& temporary) {
      CrcWriter writer(temporary);
      const std::string preamble = core::npyPreamble(part.dtype, part.shape);
      writer.write(preamble.data(), preamble.size());
      for (const DatasetInfo& shard : shards) {
        const fs::path input = shard.folder / part.file;
        const core::NpyHeader header = core::readNpyHeader(input);
        std::vector<std::int64_t> shape = part.shape;
        shape[0] = shard.settings.rows();
        PIXELCLOTH_CHECK(header.dtype == part.dtype && header.shape == shape,
                         input.string() << ": " << header.dtype << " of shape " << header.shapeString() << ", expected "
                                        << part.dtype << " of shape " << core::npyShapeString(shape));
        std::ifstream in(input, std::ios::binary);
        std::uint32_t crc = 0;
        std::int64_t position = 0;
        while (in) {
          in.read(buffer.data(), buffer.size());
          const std::int64_t n = in.gcount();
          crc = crc32Update(crc, buffer.data(), static_cast<std::size_t>(n));
          const std::int64_t skip = std::clamp<std::int64_t>(header.dataOffset - position, 0, n);
          writer.write(buffer.data() + skip, static_cast<std::size_t>(n - skip));
          position += n;
        }
        const std::uint32_t expected = shard.manifest["checksums"][part.file]["crc32"].get<std::uint32_t>();
        PIXELCLOTH_CHECK(crc == expected, input.string() << ": CRC-32 " << crc << ", its manifest.json says "
                                                         << expected << " (the file is damaged or was changed)");
        progress.advance();
      }
      const std::uint32_t crc = writer.close();
      checksums[part.file] = {{"crc32", crc}, {"bytes", writer.size()}};
    });
  }
  progress.finish();

  DatasetStats stats;
  for (const DatasetInfo& shard : shards) stats.merge(shard.stats);
  DatasetSettings merged = s;
  merged.shard = DatasetShard{};
  const std::vector<std::uint8_t> split = datasetSplit(s.seed, s.count);
  const SplitCounts counts = countSplits(split);
  json manifest = reference.manifest;
  manifest.update(merged.toJson());
  manifest["rows"] = merged.rows();
  manifest["counts"] = {{"train", counts.train}, {"regularisation", counts.regularisation}, {"test", counts.test}};
  manifest["stats"] = stats.toJson();
  manifest["checksums"] = checksums;
  for (const char* array : {"poses", "positions", "offsets", "split"})
    if (manifest.contains("arrays") && manifest["arrays"].contains(array)) manifest["arrays"][array]["shape"][0] = N;
  manifest["merged_from"] = shards.size();
  core::writeJson(staging / kManifest, manifest);
  if (fs::is_directory(out, ec)) fs::remove(out, ec);  // empty, checked above; rename needs the name free
  fs::rename(staging, out);
  cleanup.done = true;
  PIXELCLOTH_INFO("dataset merge: " << shards.size() << " shards, " << N << " samples -> " << out.string());
  return readDatasetInfo(out);
}

}  // namespace pixelcloth::data
