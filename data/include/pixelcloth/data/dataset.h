#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <type_traits>
#include <vector>

#include "pixelcloth/body/body.h"
#include "pixelcloth/body/pose_io.h"
#include "pixelcloth/core/npy.h"
#include "pixelcloth/data/sample.h"
#include "pixelcloth/garment/embedding.h"
#include "pixelcloth/garment/garment.h"

namespace pixelcloth::data {

/// Version of the dataset folder format written here (docs/dataset.md). Readers refuse other versions.
inline constexpr int kDatasetFormatVersion = 1;

/// One of `count` contiguous slices of the sample indices [0, N): shard k covers [floor(k N / count),
/// floor((k + 1) N / count)), so shards 0..count-1 tile [0, N) exactly and can run as independent jobs.
struct DatasetShard {
  int index = 0;
  int count = 1;
  int first(int total) const;  ///< first sample index of this shard
  int end(int total) const;    ///< one past its last sample index
  /// Throws `InputError` unless count >= 1 and 0 <= index < count.
  void validate() const;
  std::string toString() const;  ///< "K/N"
};

/// Parses "K/N" (e.g. "3/100", 0 <= K < N) as the command line's `--shard K/N` gives it; throws `InputError`.
DatasetShard parseShard(const std::string& text);

/// What a dataset folder holds and how it was made: everything that must agree when a partial folder is resumed or
/// shards are merged (the shard itself excepted for merging).
struct DatasetSettings {
  std::string garment = "tshirt";  ///< the garment's name, for people; the garment itself is the folder's garment/
  int poseSize = 90;               ///< 9 per driving joint: 90 (T-shirt), 36 (necktie: the four centre-line joints)
  int vertexCount = 0;             ///< cloth pixels of the garment
  std::uint64_t seed = 0;          ///< generator seed; also seeds the train / regularisation / test split
  int count = 0;                   ///< N: samples in the whole dataset (all shards)
  DatasetShard shard;              ///< which slice of [0, N) this folder holds
  nlohmann::json body = nlohmann::json::object();       ///< e.g. {"kind": "mannequin", "shape": 0}
  nlohmann::json generator = nlohmann::json::object();  ///< free-form generator settings (solver, sampler)
  std::string source = "simulated";                     ///< "simulated" | "imported"

  int first() const { return shard.first(count); }  ///< first sample index of this folder
  int end() const { return shard.end(count); }      ///< one past the last
  int rows() const { return end() - first(); }      ///< samples in this folder
  /// Throws `InputError` naming the field that is out of range (garment, pose size vs garment, counts, shard, source).
  void validate() const;
  /// The manifest's fields: garment, pose_size, vertex_count, seed, count, shard {index, count, first, end}, body,
  /// settings (the generator), source.
  nlohmann::json toJson() const;
  /// Reads what toJson writes; `context` (a file name) prefixes messages. Validates.
  static DatasetSettings fromJson(const nlohmann::json& json, const std::string& context);
  /// Manifest name of the first field that differs from `other` ("" when none), e.g. "seed" or "body"; the shard is
  /// compared unless `ignoreShard`.
  std::string firstDifference(const DatasetSettings& other, bool ignoreShard = false) const;
};

/// Split of a sample: what learn/ uses it for.
enum class Split : std::uint8_t { Train = 0, Regularisation = 1, Test = 2 };

/// "train", "regularisation", "test".
const char* splitName(Split split);
/// The split named `name` (train, regularisation or test); InputError naming `context` otherwise.
Split splitFromName(const std::string& name, const std::string& context);

/// The split of every sample index in [0, count): a seeded Fisher-Yates shuffle of 0..count-1 (mt19937_64, the same
/// on every platform) whose first round(0.8 count) entries are train, the next round(0.1 count) regularisation and
/// the rest test. Depends only on (seed, count), so a shard's rows equal the same rows of an unsharded dataset.
std::vector<std::uint8_t> datasetSplit(std::uint64_t seed, int count);

/// Samples per split.
struct SplitCounts {
  int train = 0, regularisation = 0, test = 0;
  int total() const { return train + regularisation + test; }
};
SplitCounts countSplits(const std::vector<std::uint8_t>& split);

/// Summary of the solver statistics of the accepted samples and of the rejections (manifest `stats`).
struct DatasetStats {
  int accepted = 0;
  int acceptedAfterExtra = 0;  ///< of those, accepted only after extra rounds (SampleStats::extraRounds > 0)
  double maxPenetration = 0;   ///< metres, max over samples
  /// Largest SampleStats::residualForceRatio over the samples that measured one (NaN: none did).
  double maxResidualForceRatio = std::numeric_limits<double>::quiet_NaN();
  double sumIterations = 0;
  int maxIterations = 0;
  double sumSeconds = 0;
  double minAreaRatio = std::numeric_limits<double>::infinity();
  double maxAreaRatio = 0;
  std::map<std::string, int> rejected;  ///< by rejectionName

  void add(const SampleStats& stats);
  void reject(Rejection rejection, int count = 1);
  void merge(const DatasetStats& other);
  int rejectedTotal() const;
  /// Poses simulated: the accepted ones and those the simulation rejected (the sampler's pruned draws, an arm inside
  /// the torso, were never simulated).
  int simulated() const;
  /// {"accepted", "accepted_after_extra_rounds", "max_penetration_mm", "mean_iterations", "max_iterations",
  ///  "mean_seconds", "total_seconds", "min_area_ratio", "max_area_ratio", "rejected": {reason: count},
  ///  "rejected_total"}, and "max_residual_force_ratio" when the samples measured it; area ratios are null when no
  ///  sample was accepted.
  nlohmann::json toJson() const;
  static DatasetStats fromJson(const nlohmann::json& json, const std::string& context);
};

/// CRC-32 (zlib's, as Python's `zlib.crc32` computes it) of a whole file. Throws `InputError` when unreadable.
std::uint32_t fileCrc32(const std::filesystem::path& path);

/// Options of the writer.
struct DatasetWriterOptions {
  /// Finished samples are kept in memory until this many have been added, then written as one chunk file
  /// (atomically): a killed run loses at most this many samples. In [1, 4096].
  int chunkSize = 8;
  void validate() const;
};

/// Writes a dataset folder (docs/dataset.md) sample by sample, resumable.
///
/// On construction the folder is created, or a partial one (from a run that was killed, or is being re-run) is
/// resumed when its settings are identical; a folder whose settings differ is refused with `InputError` naming the
/// field, and so is a non-empty folder that is not a dataset. A finished folder with identical settings is accepted
/// with nothing pending (finish() then does nothing). The folder gets body/ (body::saveBody), garment/
/// (garment::saveGarment), rest_positions.npy (#V x 3 float64) and the embedding arrays (garment::saveEmbedding) at
/// once; on resume they are rewritten and must come out byte-identical to what the partial folder holds.
///
/// Samples go to partial/chunk_NNNNNN.bin files (each written atomically, with a CRC); finish() assembles
/// poses.npy, positions.npy, offsets.npy, split.npy and manifest.json (manifest last) and removes partial/.
/// add() and countRejection() may be called from several threads.
class DatasetWriter {
 public:
  /// `restPositions` #V x 3 metres (the dressed garment in the rest pose); `embedding` of its #V cloth pixels.
  DatasetWriter(const std::filesystem::path& folder, const DatasetSettings& settings, const body::Body& body,
                const garment::Garment& garment, const Eigen::MatrixX3d& restPositions,
                const garment::Embedding& embedding, const DatasetWriterOptions& options = {});
  /// Writes the samples added since the last chunk (a partial chunk) so they survive; never throws.
  ~DatasetWriter();
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;

  /// Sample indices of this shard, ascending, that have not been added yet (in this run or an earlier one).
  std::vector<int> pending() const;
  /// Number of samples of this shard added so far (this run and earlier ones).
  int done() const;
  /// True when the folder held a partial (or finished) dataset with these settings.
  bool resumed() const;
  /// Adds sample `index` (in [first, end) of the shard, not added before). Checks the pose size and that its 3x3
  /// blocks are rotations, positions and offsets #V x 3, every value finite, and that the sample was not rejected.
  void add(int index, const Sample& sample);
  /// Counts a discarded sample by reason (not None). Persisted with the next chunk.
  void countRejection(Rejection rejection);
  /// The statistics of everything added and rejected so far.
  DatasetStats stats() const;
  /// When nothing is pending: writes the arrays and manifest.json atomically (manifest last) and removes the chunk
  /// files. Throws `InputError` naming the first pending index otherwise, or a chunk file that is damaged.
  void finish();

  const std::filesystem::path& folder() const;
  const DatasetSettings& settings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Whether the dataset readers check each file they open against manifest.json's size and CRC-32 before using it
/// (CRC-32 streams at GB/s, about a second per GB). A file the manifest does not list is read unchecked.
enum class Checksums { Verify, Skip };

/// A dataset folder together with how its files are to be read. Converts from a path, checked: only the CLI's
/// `--no-verify` makes a Skip folder.
struct DatasetFolder {
  template <typename Path, typename = std::enable_if_t<std::is_constructible_v<std::filesystem::path, const Path&> &&
                                                       !std::is_same_v<std::decay_t<Path>, DatasetFolder>>>
  DatasetFolder(const Path& path, Checksums checksums = Checksums::Verify) : path(path), checksums(checksums) {}

  std::filesystem::path path;
  Checksums checksums = Checksums::Verify;

  /// Another folder read the same way (a dataset's sibling, a shard).
  DatasetFolder with(const std::filesystem::path& other) const { return {other, checksums}; }
};

/// The manifest of a finished dataset folder, parsed and validated (format version, fields, counts).
struct DatasetInfo {
  std::filesystem::path folder;
  Checksums checksums = Checksums::Verify;  ///< how the files it lists are read (DatasetFolder)
  DatasetFolder where() const { return {folder, checksums}; }
  nlohmann::json manifest;
  DatasetSettings settings;
  DatasetStats stats;
  SplitCounts counts;
  /// Readable multi-line summary: garment, body, source, samples and shard, splits, stats, rejections.
  std::string summary() const;
  /// The row of sample index `sample` in this folder's arrays; InputError "<what> <sample>: <folder> holds samples
  /// <first> to <last>" for a sample it does not hold (`what` names the option, e.g. "predict --samples").
  int rowOfSample(int sample, const std::string& what) const;
};

/// Reads manifest.json of `folder`; throws `InputError` naming the file and field when it is missing or malformed.
DatasetInfo readDatasetInfo(const DatasetFolder& folder);

/// When `info.checksums` is Verify: throws `InputError` naming `info.folder / name` when its size or CRC-32 differs
/// from the manifest's (a damaged or changed file).
void verifyDatasetFile(const DatasetInfo& info, const std::string& name);

/// A finished dataset in memory. Row r of every array is sample index settings.first() + r.
struct Dataset {
  DatasetInfo info;
  Eigen::MatrixXf poses;            ///< rows x poseSize
  core::NpyArray positions;         ///< (rows, #V, 3) float32, C order (kept as read: large datasets are ~1 GB)
  core::NpyArray offsets;           ///< (rows, #V, 3) float32
  std::vector<std::uint8_t> split;  ///< rows: 0 train, 1 regularisation, 2 test

  int rows() const { return static_cast<int>(split.size()); }
  int vertexCount() const { return info.settings.vertexCount; }
  Eigen::VectorXf pose(int row) const;
  Eigen::MatrixX3f positionsOf(int row) const;  ///< #V x 3
  Eigen::MatrixX3f offsetsOf(int row) const;    ///< #V x 3
  /// Rows of one split, ascending.
  std::vector<int> rowsOf(Split split) const;
};

/// Reads a finished dataset (manifest and the four arrays, shapes and dtypes checked against the manifest; the arrays
/// verified against their checksums unless `folder.checksums` is Skip).
Dataset openDataset(const DatasetFolder& folder);

/// The dataset's body (body/), embedding (embedding_*.npy, checked against the body's faces) and rest positions, each
/// file verified against the manifest's checksums first (unless `folder.checksums` is Skip).
body::Body loadDatasetBody(const DatasetFolder& folder);
garment::Embedding loadDatasetEmbedding(const DatasetFolder& folder, int numBodyFaces);
Eigen::MatrixX3d loadDatasetRestPositions(const DatasetFolder& folder, int vertexCount);

/// A garment dressed on a body, as a dressing folder (`pixelcloth dress`) or a dataset holds it.
struct DressingFiles {
  body::Body body;
  Eigen::MatrixX3d rest;         ///< #V x 3: the relaxed rest positions on the body
  garment::Embedding embedding;  ///< #V cloth pixels in the body's triangles
};

/// The body, rest positions and embedding of a dressing folder or dataset `folder`, checked against `garment`: throws
/// InputError naming the file when its rest positions or embedding hold another vertex count (the dressing is of
/// another garment) or when a file is missing or damaged. `garmentSource` names where `garment` came from for that
/// message (e.g. "the markers (m.json)"); empty: the garment alone.
DressingFiles loadDressingFiles(const DatasetFolder& folder, const garment::Garment& garment,
                                const std::string& garmentSource = "");

/// The garment the dataset was made with, read from its garment/ folder (garment::loadGarment; checksums verified
/// first): a template or an imported garment alike. Throws `InputError` when the folder is missing or damaged, or when
/// its vertex count or pose size disagrees with the manifest.
garment::Garment datasetGarment(const DatasetInfo& info);

/// Options of checkDataset.
struct DatasetCheckOptions {
  int strongSamples = 3;    ///< samples (spread over the rows) whose offsets are recomputed from their positions
  double tolerance = 2e-5;  ///< largest accepted difference of a recomputed offset, metres
};

/// What checkDataset verified.
struct DatasetCheckReport {
  int rows = 0;
  int filesChecked = 0;       ///< files whose size and CRC-32 matched the manifest
  int strongSamples = 0;      ///< samples whose offsets were recomputed
  double maxOffsetError = 0;  ///< largest difference found there, metres
  std::string summary() const;
};

/// Verifies a finished dataset: manifest fields; every file in `checksums` present with its size and CRC-32; array
/// dtypes and shapes against the manifest; every value finite; every pose a set of rotations; split values in
/// {0, 1, 2}, equal to datasetSplit(seed, count) on the folder's rows and to the manifest's counts; and for a few
/// samples, offsets recomputed from positions on the posed stored body with the stored embedding. Throws `InputError`
/// naming the file and what is wrong.
DatasetCheckReport checkDataset(const std::filesystem::path& folder, const DatasetCheckOptions& options = {});

/// Merges finished shard folders into `out`: every shard must have the same settings except the shard, the same
/// body, garment and embedding files (byte for byte), and together they must cover [0, N) exactly, without overlap
/// or gap (any order on the command line). Arrays are concatenated in index order (streamed: memory stays small)
/// and each shard's files are verified against its checksums while being read, so the result equals an unsharded
/// run's arrays byte for byte. `out` must not exist or be empty. Returns the merged dataset's info.
DatasetInfo mergeDatasets(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out);

/// The OBJ files of a folder, in natural name order (frame_2.obj before frame_10.obj). Throws when there is none.
std::vector<std::filesystem::path> objSequence(const std::filesystem::path& folder);

/// Reads a pose sequence, one pose vector of `poseSize` (90 or 36) floats per frame, from
///  - JSON (.json): a list whose entries are pose objects as body::poseFromJson reads them ({"pose": [90]} or
///    {"joints": {...}}) or plain arrays of `poseSize` numbers; or an object {"poses": that list};
///  - CSV (any other extension): one row of `poseSize` numbers per frame, comma separated, optionally a header row.
/// For the necktie (36) rows of 90 numbers are accepted too (the first 36 are kept). Every pose's 3x3 blocks must be
/// rotations. A pose beyond the joint limits is refused, or with BeyondLimits::Clamp clamped (a warning counts them),
/// as in every verb. Throws `InputError` naming the file, the frame (or line) and the fault.
std::vector<Eigen::VectorXf> readPoseSequence(const std::filesystem::path& path, int poseSize,
                                              body::BeyondLimits beyondLimits = body::BeyondLimits::Refuse);

/// How importDataset describes what it imported.
struct ImportOptions {
  nlohmann::json body = nlohmann::json::object();  ///< the body description for the manifest
  std::uint64_t seed = 0;                          ///< seeds the split
  body::BeyondLimits beyondLimits = body::BeyondLimits::Refuse;  ///< poses beyond the joint limits
};

/// The same samples on another body (the paper's wrong-body-shape and broken-skinning experiments): `folder`'s positions
/// and poses kept, its rest positions embedded afresh on `body` at their closest points (the pattern's u-direction
/// taken from the old embedding's frames on the old rest body), and every sample's offsets recomputed in the frames
/// of that embedding on `body` posed with the sample's pose. Written through DatasetWriter into `out` (resumable) with
/// the same garment, seed, count, shard and split; the manifest's body is `bodyDescription` plus "rebased_from"
/// (the old folder, its body and its manifest CRC-32), and the generator settings are the old ones with
/// "rebased_stats" (the old solver statistics, which the new per-sample stats cannot carry). Throws `InputError`
/// for a body whose skeleton differs from the dataset's body's (joint names and order), naming both.
DatasetSettings rebaseDataset(const DatasetFolder& folder, const body::Body& body,
                              const nlohmann::json& bodyDescription, const std::filesystem::path& out);

/// Imports garment shapes from another simulator or from capture: `objs` (one garment mesh per frame, the same
/// vertex count and the same faces as `garment.mesh`, finite) with `poses` (readPoseSequence; as many as OBJs).
/// Everything is validated before the dataset is written. Offsets are computed from the positions in the frames of
/// `embedding` on the posed `body`; per-sample stats record the triangle area ratios. Written through DatasetWriter
/// (source "imported", resumable) into `out`. Returns the settings it wrote.
DatasetSettings importDataset(const std::vector<std::filesystem::path>& objs, const std::filesystem::path& poses,
                              const body::Body& body, const garment::Garment& garment,
                              const Eigen::MatrixX3d& restPositions, const garment::Embedding& embedding,
                              const std::filesystem::path& out, const ImportOptions& options = {});

}  // namespace pixelcloth::data
