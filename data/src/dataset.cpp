// Dataset settings, shards, splits, statistics and the resumable writer.
#include "pixelcloth/data/dataset.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <mutex>
#include <random>
#include <regex>
#include <set>

#include "dataset_internal.h"
#include "pixelcloth/body/skeleton.h"
#include "pixelcloth/core/atomic_file.h"
#include "pixelcloth/core/enum_names.h"
#include "pixelcloth/core/error.h"
#include "pixelcloth/core/json_io.h"
#include "pixelcloth/core/log.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/core/progress.h"
#include "pixelcloth/core/run_folder.h"

namespace pixelcloth::data {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace detail;

// ---------------------------------------------------------------------------------------------------------------------
// Shards, settings, splits, statistics

int DatasetShard::first(int total) const { return static_cast<int>(std::int64_t(index) * total / count); }
int DatasetShard::end(int total) const { return static_cast<int>(std::int64_t(index + 1) * total / count); }

void DatasetShard::validate() const {
  PIXELCLOTH_CHECK(count >= 1 && index >= 0 && index < count,
                   "shard " << index << "/" << count << ": expected K/N with N >= 1 and 0 <= K < N");
}

std::string DatasetShard::toString() const { return std::to_string(index) + "/" + std::to_string(count); }

DatasetShard parseShard(const std::string& text) {
  std::smatch m;
  PIXELCLOTH_CHECK(std::regex_match(text, m, std::regex("\\s*(\\d{1,9})\\s*/\\s*(\\d{1,9})\\s*")),
                   "--shard '" << text << "': expected K/N, e.g. 3/100 (shard K of N, counted from 0)");
  DatasetShard shard{std::stoi(m[1]), std::stoi(m[2])};
  PIXELCLOTH_CHECK(shard.count >= 1 && shard.index < shard.count,
                   "--shard '" << text << "': expected 0 <= K < N (shards are counted from 0)");
  return shard;
}

void DatasetSettings::validate() const {
  PIXELCLOTH_CHECK(!garment.empty(), "dataset settings: garment is empty, expected the garment's name");
  PIXELCLOTH_CHECK(poseSize >= 9 && poseSize <= body::kPoseSize && poseSize % 9 == 0,
                   "dataset settings: pose_size " << poseSize << ", expected 9 floats (a 3x3 rotation) for each of 1 to "
                                                  << body::kPoseSize / 9 << " joints");
  PIXELCLOTH_CHECK(vertexCount > 0, "dataset settings: vertex_count " << vertexCount << ", expected > 0");
  PIXELCLOTH_CHECK(count >= 1, "dataset settings: count " << count << ", expected >= 1");
  shard.validate();
  PIXELCLOTH_CHECK(shard.count <= count, "dataset settings: " << shard.count << " shards for " << count
                                                              << " samples; expected at most one "
                                                              << "shard per sample");
  PIXELCLOTH_CHECK(source == "simulated" || source == "imported",
                   "dataset settings: source '" << source << "', expected simulated or imported");
  PIXELCLOTH_CHECK(body.is_object(), "dataset settings: body must be a JSON object");
  PIXELCLOTH_CHECK(generator.is_object(), "dataset settings: settings (generator) must be a JSON object");
}

json DatasetSettings::toJson() const {
  return json{{"garment", garment},
              {"pose_size", poseSize},
              {"vertex_count", vertexCount},
              {"seed", seed},
              {"count", count},
              {"shard", {{"index", shard.index}, {"count", shard.count}, {"first", first()}, {"end", end()}}},
              {"body", body},
              {"settings", generator},
              {"source", source}};
}

DatasetSettings DatasetSettings::fromJson(const json& j, const std::string& context) {
  DatasetSettings s;
  s.garment = core::requireValue<std::string>(j, "garment", context);
  s.poseSize = core::requireValue<int>(j, "pose_size", context);
  s.vertexCount = core::requireValue<int>(j, "vertex_count", context);
  s.seed = core::requireValue<std::uint64_t>(j, "seed", context);
  s.count = core::requireValue<int>(j, "count", context);
  const json& shard = core::requireField(j, "shard", context);
  s.shard.index = core::requireValue<int>(shard, "index", context + ": shard");
  s.shard.count = core::requireValue<int>(shard, "count", context + ": shard");
  s.body = core::requireField(j, "body", context);
  s.generator = core::requireField(j, "settings", context);
  s.source = core::requireValue<std::string>(j, "source", context);
  try {
    s.validate();
  } catch (const core::InputError& e) {
    PIXELCLOTH_FAIL(context << ": " << e.what());
  }
  if (shard.contains("first") || shard.contains("end")) {
    PIXELCLOTH_CHECK(core::requireValue<int>(shard, "first", context + ": shard") == s.first() &&
                         core::requireValue<int>(shard, "end", context + ": shard") == s.end(),
                     context << ": shard range [" << core::requireValue<int>(shard, "first", context) << ", " << core::requireValue<int>(shard, "end", context)
                             << ") does not match shard " << s.shard.toString() << " of " << s.count << " samples ["
                             << s.first() << ", " << s.end() << ")");
  }
  return s;
}

std::string DatasetSettings::firstDifference(const DatasetSettings& other, bool ignoreShard) const {
  if (garment != other.garment) return "garment";
  if (poseSize != other.poseSize) return "pose_size";
  if (vertexCount != other.vertexCount) return "vertex_count";
  if (seed != other.seed) return "seed";
  if (count != other.count) return "count";
  if (!ignoreShard && (shard.index != other.shard.index || shard.count != other.shard.count)) return "shard";
  if (body != other.body) return "body";
  if (generator != other.generator) return "settings";
  if (source != other.source) return "source";
  return "";
}

namespace {
const core::EnumNames<Split, 3> kSplits{
    "split", {{{Split::Train, "train"}, {Split::Regularisation, "regularisation"}, {Split::Test, "test"}}}};
}  // namespace

const char* splitName(Split split) { return kSplits.name(split); }
Split splitFromName(const std::string& name, const std::string& context) { return kSplits.fromName(name, context); }

std::vector<std::uint8_t> datasetSplit(std::uint64_t seed, int count) {
  PIXELCLOTH_CHECK(count >= 0, "split: negative sample count " << count);
  std::vector<int> order(count);
  for (int i = 0; i < count; ++i) order[i] = i;
  // Fisher-Yates with mt19937_64 and a plain modulo: std::shuffle and the std distributions differ between standard
  // libraries, and shards may be made on different machines.
  std::mt19937_64 rng(seed ^ 0x5eed5b1175ULL);
  for (int i = count - 1; i > 0; --i) std::swap(order[i], order[rng() % std::uint64_t(i + 1)]);
  const int train = static_cast<int>(std::llround(0.8 * count));
  const int regularisation = std::min(count - train, static_cast<int>(std::llround(0.1 * count)));
  std::vector<std::uint8_t> split(count);
  for (int k = 0; k < count; ++k) split[order[k]] = k < train ? 0 : k < train + regularisation ? 1 : 2;
  return split;
}

SplitCounts countSplits(const std::vector<std::uint8_t>& split) {
  SplitCounts counts;
  for (std::uint8_t s : split) {
    if (s == 0) ++counts.train;
    if (s == 1) ++counts.regularisation;
    if (s == 2) ++counts.test;
  }
  return counts;
}

void DatasetStats::add(const SampleStats& s) {
  DatasetStats one;  // the statistics of this sample alone
  one.accepted = 1;
  one.acceptedAfterExtra = s.extraRounds > 0 ? 1 : 0;
  one.maxPenetration = s.maxPenetration;
  one.maxResidualForceRatio = s.residualForceRatio;
  one.sumIterations = one.maxIterations = s.iterations;
  one.sumSeconds = s.seconds;
  one.minAreaRatio = s.minAreaRatio;
  one.maxAreaRatio = s.maxAreaRatio;
  merge(one);
}

void DatasetStats::reject(Rejection rejection, int count) { rejected[rejectionName(rejection)] += count; }

void DatasetStats::merge(const DatasetStats& o) {
  accepted += o.accepted;
  acceptedAfterExtra += o.acceptedAfterExtra;
  maxPenetration = std::max(maxPenetration, o.maxPenetration);
  maxResidualForceRatio = std::fmax(maxResidualForceRatio, o.maxResidualForceRatio);  // NaN: not measured
  sumIterations += o.sumIterations;
  maxIterations = std::max(maxIterations, o.maxIterations);
  sumSeconds += o.sumSeconds;
  minAreaRatio = std::min(minAreaRatio, o.minAreaRatio);
  maxAreaRatio = std::max(maxAreaRatio, o.maxAreaRatio);
  for (const auto& [reason, n] : o.rejected) rejected[reason] += n;
}

int DatasetStats::rejectedTotal() const {
  int total = 0;
  for (const auto& entry : rejected) total += entry.second;
  return total;
}

int DatasetStats::simulated() const {
  const auto pruned = rejected.find(rejectionName(Rejection::ArmInsideTorso));
  return accepted + rejectedTotal() - (pruned == rejected.end() ? 0 : pruned->second);
}

json DatasetStats::toJson() const {
  const bool any = accepted > 0;
  json rejectedJson = json::object();
  for (const auto& [reason, n] : rejected) rejectedJson[reason] = n;
  json result{{"accepted", accepted},
              {"accepted_after_extra_rounds", acceptedAfterExtra},
              {"max_penetration_mm", maxPenetration * 1000.0},
              {"mean_iterations", any ? sumIterations / accepted : 0.0},
              {"max_iterations", maxIterations},
              {"mean_seconds", any ? sumSeconds / accepted : 0.0},
              {"total_seconds", sumSeconds},
              {"min_area_ratio", any ? json(minAreaRatio) : json(nullptr)},
              {"max_area_ratio", any ? json(maxAreaRatio) : json(nullptr)},
              {"rejected", rejectedJson},
              {"rejected_total", rejectedTotal()}};
  if (std::isfinite(maxResidualForceRatio)) result["max_residual_force_ratio"] = maxResidualForceRatio;
  return result;
}

DatasetStats DatasetStats::fromJson(const json& j, const std::string& context) {
  DatasetStats s;
  s.accepted = core::requireValue<int>(j, "accepted", context);
  s.acceptedAfterExtra = core::valueOr<int>(j, "accepted_after_extra_rounds", 0, context);  // absent before it
  s.maxPenetration = core::requireValue<double>(j, "max_penetration_mm", context) / 1000.0;
  if (j.contains("max_residual_force_ratio"))  // only the Newton solver measures it
    s.maxResidualForceRatio = core::requireValue<double>(j, "max_residual_force_ratio", context);
  s.sumIterations = core::requireValue<double>(j, "mean_iterations", context) * s.accepted;
  s.maxIterations = core::requireValue<int>(j, "max_iterations", context);
  s.sumSeconds = core::requireValue<double>(j, "total_seconds", context);
  if (s.accepted > 0) {
    s.minAreaRatio = core::requireValue<double>(j, "min_area_ratio", context);
    s.maxAreaRatio = core::requireValue<double>(j, "max_area_ratio", context);
  }
  const json& rejected = core::requireField(j, "rejected", context);
  PIXELCLOTH_CHECK(rejected.is_object(), context << ": field 'rejected' must be an object {reason: count}");
  for (const auto& [reason, n] : rejected.items())
    s.rejected[reason] = core::requireValue<int>(rejected, reason, context + ": rejected");
  return s;
}

void DatasetWriterOptions::validate() const {
  PIXELCLOTH_CHECK(chunkSize >= 1 && chunkSize <= 4096,
                   "dataset writer: chunk size " << chunkSize << ", expected 1 to 4096");
}

// ---------------------------------------------------------------------------------------------------------------------
// Chunk files: "PXCHUNK1", uint32 header length, JSON header {indices, stats, rejected, pose_size, vertex_count},
// then per sample pose (pose_size floats), positions and offsets (#V x 3 floats each, row-major), then the CRC-32 of
// everything before it (uint32, little endian).

namespace {

constexpr char kChunkMagic[8] = {'P', 'X', 'C', 'H', 'U', 'N', 'K', '1'};

struct ChunkRecord {
  int index = 0;
  SampleStats stats;
};

struct ChunkFile {
  fs::path path;
  std::int64_t dataOffset = 0;
  std::vector<ChunkRecord> records;
  std::map<std::string, int> rejected;
};

json statsToJson(const SampleStats& s) {
  json result{{"iterations", s.iterations},
              {"extra_rounds", s.extraRounds},
              {"residual", s.residual},
              {"max_penetration", s.maxPenetration},
              {"min_area_ratio", s.minAreaRatio},
              {"max_area_ratio", s.maxAreaRatio},
              {"seconds", s.seconds}};
  if (std::isfinite(s.residualForceRatio)) {
    result["max_residual_force_n"] = s.maxResidualForce;
    result["residual_force_ratio"] = s.residualForceRatio;
  }
  return result;
}

SampleStats statsFromJson(const json& j, const std::string& context) {
  SampleStats s;
  s.iterations = core::requireValue<int>(j, "iterations", context);
  s.extraRounds = core::valueOr<int>(j, "extra_rounds", 0, context);  // absent in datasets made before it
  s.residual = core::requireValue<double>(j, "residual", context);
  if (j.contains("residual_force_ratio")) {  // only the Newton solver measures it
    s.maxResidualForce = core::requireValue<double>(j, "max_residual_force_n", context);
    s.residualForceRatio = core::requireValue<double>(j, "residual_force_ratio", context);
  }
  s.maxPenetration = core::requireValue<double>(j, "max_penetration", context);
  s.minAreaRatio = core::requireValue<double>(j, "min_area_ratio", context);
  s.maxAreaRatio = core::requireValue<double>(j, "max_area_ratio", context);
  s.seconds = core::requireValue<double>(j, "seconds", context);
  return s;
}

std::int64_t recordFloats(const DatasetSettings& s) { return s.poseSize + 6LL * s.vertexCount; }

/// Reads a chunk's header and checks its length against the file (the CRC is checked by verifyChunk).
ChunkFile readChunkHeader(const fs::path& path, const DatasetSettings& settings) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  PIXELCLOTH_CHECK(in, file << ": cannot open for reading");
  char magic[8];
  std::uint32_t length = 0;
  in.read(magic, 8);
  in.read(reinterpret_cast<char*>(&length), 4);
  PIXELCLOTH_CHECK(in && std::memcmp(magic, kChunkMagic, 8) == 0 && length < (1u << 30),
                   file << ": not a dataset chunk file (bad magic); remove it to regenerate its samples");
  std::string text(length, '\0');
  in.read(text.data(), length);
  PIXELCLOTH_CHECK(in, file << ": truncated chunk header; remove it to regenerate its samples");
  const json header = core::parseJson(text, file + ": chunk header (remove the file to regenerate its samples)");
  ChunkFile chunk;
  chunk.path = path;
  chunk.dataOffset = 12 + length;
  PIXELCLOTH_CHECK(core::requireValue<int>(header, "pose_size", file) == settings.poseSize &&
                       core::requireValue<int>(header, "vertex_count", file) == settings.vertexCount,
                   file << ": chunk of another pose size or vertex count than the dataset's settings");
  const auto indices = core::requireValue<std::vector<int>>(header, "indices", file);
  const json& stats = core::requireField(header, "stats", file);
  PIXELCLOTH_CHECK(stats.is_array() && stats.size() == indices.size(), file << ": stats do not match indices");
  for (size_t k = 0; k < indices.size(); ++k)
    chunk.records.push_back({indices[k], statsFromJson(stats[k], file + ": stats")});
  for (const auto& [reason, n] : core::requireField(header, "rejected", file).items())
    chunk.rejected[reason] = n.get<int>();
  std::error_code ec;
  const std::int64_t expected = chunk.dataOffset + std::int64_t(indices.size()) * recordFloats(settings) * 4 + 4;
  PIXELCLOTH_CHECK(static_cast<std::int64_t>(fs::file_size(path, ec)) == expected,
                   file << ": " << fs::file_size(path, ec) << " bytes, expected " << expected
                        << " for its samples; remove it to regenerate them");
  return chunk;
}

/// Checks the CRC-32 at the end of a chunk file.
void verifyChunk(const fs::path& path) {
  std::error_code ec;
  const std::int64_t size = static_cast<std::int64_t>(fs::file_size(path, ec));
  std::ifstream in(path, std::ios::binary);
  std::vector<char> buffer(1 << 20);
  std::uint32_t crc = 0;
  std::int64_t left = size - 4;
  while (left > 0 && in) {
    const std::int64_t n = std::min<std::int64_t>(left, buffer.size());
    in.read(buffer.data(), n);
    crc = crc32Update(crc, buffer.data(), static_cast<std::size_t>(in.gcount()));
    left -= in.gcount();
  }
  std::uint32_t stored = 0;
  in.read(reinterpret_cast<char*>(&stored), 4);
  PIXELCLOTH_CHECK(in && stored == crc, path.string() << ": chunk CRC-32 mismatch (damaged file); remove it to "
                                                      << "regenerate its samples");
}

bool pathContains(const std::string& name, const std::string& part) { return name.find(part) != std::string::npos; }

/// Writes what describes the garment on the body (body/, garment/, rest positions, embedding) into `folder`.
void writeShared(const fs::path& folder, const body::Body& body, const garment::Garment& garment,
                 const Eigen::MatrixX3d& restPositions, const garment::Embedding& embedding,
                 const std::string& bodyText) {
  body::saveBody(folder / "body", body, bodyText);
  garment::saveGarment(folder / "garment", garment);
  core::writeNpy(folder / kRestPositions, Eigen::MatrixXd(restPositions));
  garment::saveEmbedding(folder, embedding);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------------
// DatasetWriter

struct DatasetWriter::Impl {
  fs::path folder;
  DatasetSettings settings;
  DatasetWriterOptions options;
  bool resumed = false;
  bool finished = false;  // the folder holds a finished dataset (manifest.json)

  mutable std::mutex mutex;
  std::vector<bool> done;  // per row of the shard
  int doneCount = 0;
  DatasetStats stats;
  int nextChunk = 0;
  // Not yet persisted:
  std::vector<ChunkRecord> buffered;
  std::vector<float> bufferedData;
  std::map<std::string, int> bufferedRejections;

  fs::path partial() const { return folder / kPartial; }

  void open(const body::Body& body, const garment::Garment& garment, const Eigen::MatrixX3d& rest,
            const garment::Embedding& embedding);
  void flushLocked();
};

DatasetWriter::DatasetWriter(const fs::path& folder, const DatasetSettings& settings, const body::Body& body,
                             const garment::Garment& garment, const Eigen::MatrixX3d& restPositions,
                             const garment::Embedding& embedding, const DatasetWriterOptions& options)
    : impl_(std::make_unique<Impl>()) {
  settings.validate();
  options.validate();
  PIXELCLOTH_CHECK(garment.name == settings.garment, folder.string() << ": the garment is a " << garment.name
                                                                     << ", the settings say " << settings.garment);
  PIXELCLOTH_CHECK(garment.mesh.numVertices() == settings.vertexCount,
                   folder.string() << ": the garment has " << garment.mesh.numVertices()
                                   << " vertices, the settings say vertex_count " << settings.vertexCount);
  PIXELCLOTH_CHECK(restPositions.rows() == settings.vertexCount && restPositions.allFinite(),
                   folder.string() << ": rest positions have " << restPositions.rows() << " rows (finite: "
                                   << restPositions.allFinite() << "), expected " << settings.vertexCount);
  PIXELCLOTH_CHECK(embedding.size() == settings.vertexCount, folder.string()
                                                                 << ": the embedding has " << embedding.size()
                                                                 << " cloth pixels, expected " << settings.vertexCount);
  embedding.validate(body.mesh.numFaces(), folder.string() + ": embedding");
  impl_->folder = folder;
  impl_->settings = settings;
  impl_->options = options;
  impl_->done.assign(settings.rows(), false);
  impl_->open(body, garment, restPositions, embedding);
}

void DatasetWriter::Impl::open(const body::Body& body, const garment::Garment& garment, const Eigen::MatrixX3d& rest,
                               const garment::Embedding& embedding) {
  core::checkOutputFolder(folder);
  core::checkRunFolder(folder, {"manifest.json", {{"format", "pixelcloth.dataset"}}, "a dataset"});
  const std::string bodyText = "dataset body: " + settings.body.dump();
  std::error_code ec;
  const fs::path manifest = folder / kManifest, settingsFile = partial() / "settings.json";
  const bool hasManifest = fs::exists(manifest, ec), hasPartial = fs::exists(settingsFile, ec);
  if (!hasManifest && !hasPartial) {
    if (fs::is_directory(folder, ec)) {
      for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        // What a run killed while creating the folder leaves: the shared files, written before settings.json.
        const bool ours = name == "body" || name == "garment" || name == kPartial || name == kRestPositions ||
                          name.rfind("embedding_", 0) == 0;
        PIXELCLOTH_CHECK(ours, folder.string() << ": is not empty and holds no dataset (found '" << name
                                               << "'); expected a new folder, an empty one or a dataset to resume");
      }
    }
    writeShared(folder, body, garment, rest, embedding, bodyText);
    core::writeJson(settingsFile, settings.toJson());
    return;
  }
  resumed = true;
  const fs::path stored = hasManifest ? manifest : settingsFile;
  const DatasetSettings old = DatasetSettings::fromJson(core::readJson(stored), stored.string());
  const std::string differs = settings.firstDifference(old);
  PIXELCLOTH_CHECK(differs.empty(), stored.string() << ": the dataset in this folder was made with another '" << differs
                                                    << "' (" << old.toJson()[differs].dump() << " there, "
                                                    << settings.toJson()[differs].dump()
                                                    << " now); use another folder or the same settings to resume");
  // The body, garment and dressing must be the ones the stored samples were made with.
  const fs::path check = partial() / ("check-" + std::to_string(::getpid()));
  fs::remove_all(check, ec);
  writeShared(check, body, garment, rest, embedding, bodyText);
  for (const std::string& file : sharedFiles(check)) {
    if (!fs::exists(folder / file, ec) && !hasManifest) {
      fs::create_directories((folder / file).parent_path(), ec);
      fs::rename(check / file, folder / file, ec);
      continue;
    }
    if (!byteComparable(file)) continue;
    if (!sameBytes(check / file, folder / file)) {
      fs::remove_all(check, ec);
      PIXELCLOTH_FAIL((folder / file).string() << ": differs from what this run's body, garment and dressing give; "
                                               << "the partial dataset was made with another body or dressing");
    }
  }
  fs::remove_all(check, ec);
  if (hasManifest) {
    finished = true;
    std::fill(done.begin(), done.end(), true);
    doneCount = static_cast<int>(done.size());
    return;
  }
  std::vector<fs::path> chunks;
  for (const auto& entry : fs::directory_iterator(partial())) {
    const std::string name = entry.path().filename().string();
    if (pathContains(name, ".tmp-")) {
      fs::remove(entry.path(), ec);  // a chunk being written when the run was killed
    } else if (name.rfind("chunk_", 0) == 0) {
      chunks.push_back(entry.path());
    }
  }
  std::sort(chunks.begin(), chunks.end());
  for (const fs::path& path : chunks) {
    ChunkFile chunk = readChunkHeader(path, settings);
    for (const ChunkRecord& record : chunk.records) {
      const int row = record.index - settings.first();
      PIXELCLOTH_CHECK(row >= 0 && row < settings.rows() && !done[row],
                       path.string() << ": sample " << record.index << " is outside this shard or stored twice");
      done[row] = true;
      ++doneCount;
      stats.add(record.stats);
    }
    for (const auto& [reason, n] : chunk.rejected) stats.rejected[reason] += n;
    const std::string stem = path.stem().string();
    nextChunk = std::max(nextChunk, std::stoi(stem.substr(6)) + 1);
  }
  PIXELCLOTH_INFO("dataset: resuming " << folder.string() << ": " << doneCount << " of " << settings.rows()
                                       << " samples already done");
}

void DatasetWriter::Impl::flushLocked() {
  if (buffered.empty() && bufferedRejections.empty()) return;
  json header{{"pose_size", settings.poseSize}, {"vertex_count", settings.vertexCount}};
  json indices = json::array(), statsJson = json::array();
  for (const ChunkRecord& r : buffered) {
    indices.push_back(r.index);
    statsJson.push_back(statsToJson(r.stats));
  }
  header["indices"] = indices;
  header["stats"] = statsJson;
  header["rejected"] = bufferedRejections;
  const std::string text = header.dump();
  char name[32];
  std::snprintf(name, sizeof(name), "chunk_%06d.bin", nextChunk);
  core::writeAtomically(partial() / name, [&](const fs::path& temporary) {
    CrcWriter out(temporary);
    const std::uint32_t length = static_cast<std::uint32_t>(text.size());
    out.write(kChunkMagic, 8);
    out.write(&length, 4);
    out.write(text.data(), text.size());
    out.write(bufferedData.data(), bufferedData.size() * sizeof(float));
    const std::uint32_t crc = out.crc();  // of everything before the trailer
    out.write(&crc, 4);
    out.close();
  });
  ++nextChunk;
  buffered.clear();
  bufferedData.clear();
  bufferedRejections.clear();
}

DatasetWriter::~DatasetWriter() {
  if (!impl_) return;
  try {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    if (!impl_->finished) impl_->flushLocked();
  } catch (const std::exception& e) {
    PIXELCLOTH_WARN("dataset: could not save the last samples: " << e.what());
  }
}

std::vector<int> DatasetWriter::pending() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  std::vector<int> indices;
  for (int row = 0; row < static_cast<int>(impl_->done.size()); ++row)
    if (!impl_->done[row]) indices.push_back(impl_->settings.first() + row);
  return indices;
}

int DatasetWriter::done() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->doneCount;
}

bool DatasetWriter::resumed() const { return impl_->resumed; }
const fs::path& DatasetWriter::folder() const { return impl_->folder; }
const DatasetSettings& DatasetWriter::settings() const { return impl_->settings; }

DatasetStats DatasetWriter::stats() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  DatasetStats s = impl_->stats;
  return s;
}

void DatasetWriter::add(int index, const Sample& sample) {
  const DatasetSettings& s = impl_->settings;
  const std::string context = impl_->folder.string() + ": sample " + std::to_string(index);
  PIXELCLOTH_CHECK(index >= s.first() && index < s.end(),
                   context << " is outside this shard's indices [" << s.first() << ", " << s.end() << ")");
  PIXELCLOTH_CHECK(sample.stats.rejection == Rejection::None, context << " was rejected ("
                                                                      << rejectionName(sample.stats.rejection)
                                                                      << "); count it with countRejection instead");
  PIXELCLOTH_CHECK(sample.pose.size() == s.poseSize,
                   context << ": pose has " << sample.pose.size() << " floats, expected " << s.poseSize);
  body::Pose::fromLeading(sample.pose, context + ": pose");
  PIXELCLOTH_CHECK(sample.positions.rows() == s.vertexCount && sample.offsets.rows() == s.vertexCount,
                   context << ": positions have " << sample.positions.rows() << " rows and offsets "
                           << sample.offsets.rows() << ", expected " << s.vertexCount);
  PIXELCLOTH_CHECK(sample.positions.allFinite(), context << ": positions are not finite");
  PIXELCLOTH_CHECK(sample.offsets.allFinite(), context << ": offsets are not finite");
  const SampleStats& st = sample.stats;
  PIXELCLOTH_CHECK(std::isfinite(st.residual) && std::isfinite(st.maxPenetration) && std::isfinite(st.minAreaRatio) &&
                       std::isfinite(st.maxAreaRatio) && std::isfinite(st.seconds),
                   context << ": solver statistics are not finite");

  std::lock_guard<std::mutex> lock(impl_->mutex);
  PIXELCLOTH_CHECK(!impl_->finished, context << ": the dataset is already finished");
  const int row = index - s.first();
  PIXELCLOTH_CHECK(!impl_->done[row], context << " was already added");
  impl_->done[row] = true;
  ++impl_->doneCount;
  impl_->stats.add(st);
  impl_->buffered.push_back({index, st});
  std::vector<float>& data = impl_->bufferedData;
  data.insert(data.end(), sample.pose.data(), sample.pose.data() + s.poseSize);
  // Row-major #V x 3, as the .npy arrays store it.
  for (const Eigen::MatrixX3f* m : {&sample.positions, &sample.offsets}) {
    for (int v = 0; v < s.vertexCount; ++v)
      for (int c = 0; c < 3; ++c) data.push_back((*m)(v, c));
  }
  if (static_cast<int>(impl_->buffered.size()) >= impl_->options.chunkSize) impl_->flushLocked();
}

void DatasetWriter::countRejection(Rejection rejection) {
  PIXELCLOTH_CHECK(rejection != Rejection::None, impl_->folder.string() << ": countRejection needs a reason, not none");
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->stats.reject(rejection);
  ++impl_->bufferedRejections[rejectionName(rejection)];
}

void DatasetWriter::finish() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  Impl& m = *impl_;
  if (m.finished) return;
  const DatasetSettings& s = m.settings;
  for (int row = 0; row < static_cast<int>(m.done.size()); ++row) {
    PIXELCLOTH_CHECK(m.done[row], m.folder.string() << ": cannot finish: " << s.rows() - m.doneCount
                                                    << " samples are still pending (first: " << s.first() + row << ")");
  }
  m.flushLocked();

  // Where each sample is: chunk and record.
  struct Location {
    int chunk = -1;
    std::int64_t offset = 0;
  };
  std::vector<Location> where(s.rows());
  std::vector<fs::path> chunks;
  for (const auto& entry : fs::directory_iterator(m.partial()))
    if (entry.path().filename().string().rfind("chunk_", 0) == 0 && !pathContains(entry.path().string(), ".tmp-"))
      chunks.push_back(entry.path());
  std::sort(chunks.begin(), chunks.end());
  const std::int64_t recordBytes = recordFloats(s) * 4;
  for (int c = 0; c < static_cast<int>(chunks.size()); ++c) {
    verifyChunk(chunks[c]);
    ChunkFile chunk = readChunkHeader(chunks[c], s);
    for (size_t k = 0; k < chunk.records.size(); ++k) {
      const int row = chunk.records[k].index - s.first();
      PIXELCLOTH_CHECK(row >= 0 && row < s.rows() && where[row].chunk < 0,
                       chunks[c].string() << ": sample " << chunk.records[k].index << " outside the shard or twice");
      where[row] = {c, chunk.dataOffset + std::int64_t(k) * recordBytes};
    }
  }
  for (int row = 0; row < s.rows(); ++row)
    PIXELCLOTH_CHECK(where[row].chunk >= 0, m.folder.string()
                                                << ": sample " << s.first() + row << " is in no chunk file");

  std::vector<std::ifstream> inputs;
  for (const fs::path& path : chunks) inputs.emplace_back(path, std::ios::binary);
  const std::int64_t rows = s.rows(), V = s.vertexCount;
  json checksums = json::object();
  core::Progress progress("dataset: writing arrays", 3 * rows);
  // One array at a time, rows in index order: memory stays at one sample.
  struct Part {
    const char* file;
    std::int64_t offsetFloats, floats;
    std::vector<std::int64_t> shape;
  };
  const std::vector<Part> parts = {{kPoses, 0, s.poseSize, {rows, s.poseSize}},
                                   {kPositions, s.poseSize, 3 * V, {rows, V, 3}},
                                   {kOffsets, s.poseSize + 3 * V, 3 * V, {rows, V, 3}}};
  std::vector<float> buffer;
  for (const Part& part : parts) {
    const fs::path target = m.folder / part.file;
    core::writeAtomically(target, [&](const fs::path& temporary) {
      CrcWriter out(temporary);
      const std::string preamble = core::npyPreamble("<f4", part.shape);
      out.write(preamble.data(), preamble.size());
      buffer.resize(part.floats);
      for (int row = 0; row < rows; ++row) {
        const Location& at = where[row];
        readAt(inputs[at.chunk], chunks[at.chunk], at.offset + part.offsetFloats * 4, buffer.data(), part.floats * 4);
        out.write(buffer.data(), part.floats * 4);
        progress.advance();
      }
      const std::uint32_t crc = out.close();
      checksums[part.file] = {{"crc32", crc}, {"bytes", out.size()}};
    });
  }
  progress.finish();
  const std::vector<std::uint8_t> all = datasetSplit(s.seed, s.count);
  const std::vector<std::uint8_t> split(all.begin() + s.first(), all.begin() + s.end());
  core::writeNpy(m.folder / kSplit, split, {rows});
  for (const std::string& file : std::vector<std::string>{kSplit})
    checksums[file] = {{"crc32", fileCrc32(m.folder / file)}, {"bytes", fs::file_size(m.folder / file)}};
  for (const std::string& file : sharedFiles(m.folder))
    checksums[file] = {{"crc32", fileCrc32(m.folder / file)}, {"bytes", fs::file_size(m.folder / file)}};

  const SplitCounts counts = countSplits(split);
  json manifest = {{"format", "pixelcloth.dataset"}, {"format_version", kDatasetFormatVersion}};
  manifest.update(s.toJson());
  manifest["rows"] = rows;
  manifest["counts"] = {{"train", counts.train}, {"regularisation", counts.regularisation}, {"test", counts.test}};
  manifest["stats"] = m.stats.toJson();
  manifest["checksums"] = checksums;
  manifest["arrays"] = {
      {"poses", {{"file", kPoses}, {"dtype", "<f4"}, {"shape", {rows, s.poseSize}}}},
      {"positions", {{"file", kPositions}, {"dtype", "<f4"}, {"shape", {rows, V, 3}}, {"units", "metres"}}},
      {"offsets", {{"file", kOffsets}, {"dtype", "<f4"}, {"shape", {rows, V, 3}}, {"columns", {"du", "dv", "dn"}}}},
      {"split",
       {{"file", kSplit}, {"dtype", "|u1"}, {"shape", {rows}}, {"values", {"train", "regularisation", "test"}}}},
      {"rest_positions", {{"file", kRestPositions}, {"dtype", "<f8"}, {"shape", {V, 3}}}}};
  core::writeJson(m.folder / kManifest, manifest);
  inputs.clear();
  std::error_code ec;
  fs::remove_all(m.partial(), ec);
  m.finished = true;
  PIXELCLOTH_INFO("dataset: " << rows << " samples (" << counts.train << " train, " << counts.regularisation
                              << " regularisation, " << counts.test << " test) -> " << m.folder.string());
}

}  // namespace pixelcloth::data
