// Detection of one dataset into one results CSV, as `binpick detect --dataset` does it
// (detect_batch: resumable per scene, fingerprinted by the model's checksum and the parameters).
#pragma once

#include <filesystem>

#include "host/detect/batch/detect_batch.hpp"
#include "host/detect/detector.hpp"
#include "host/train/model_store.hpp"

namespace binpick {

// Every scene of DATASET/test (or `scenes`, ascending) with `detector`, whose model is `model`,
// into csv (its directory is created). Progress on stderr. With a shard: its share of the
// scenes, csv merged only once every shard's scenes are done (BatchSummary::missing).
BatchSummary detect_to_csv(Detector& detector, const TrainedModel& model,
                           const std::filesystem::path& dataset, const std::filesystem::path& csv,
                           const Shard& shard = {}, const std::vector<int>& scenes = {});

}  // namespace binpick
