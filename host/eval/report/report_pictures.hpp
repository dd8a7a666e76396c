// The pictures of the report: for the first few images of each dataset that have results,
// depth in false colour, intensity, hypotheses, detections, the top detection's close-up and
// the first picks where eval judged them.
#pragma once

#include <string>
#include <vector>

#include "host/eval/eval_run.hpp"
#include "host/eval/report/scene_pictures.hpp"

namespace binpick::eval {

struct PicturedImage {
  std::size_t dataset = 0;  // index into the evaluations
  ImageKey key;
  DepthRange depth_range;
  // Paths relative to the report directory, in the order shown.
  std::string depth, intensity, hypotheses, detections, closeup;
  std::string picks;                      // with judged picks in the image
  std::vector<const PickOutcome*> judged;  // those picks, into the evaluation
};

// Writes options.pictures images' pictures of evaluation (index d) into options.out/pictures.
// An image whose depth cannot be read is skipped with a message in warnings.
std::vector<PicturedImage> write_pictures(const DatasetEvaluation& evaluation, std::size_t d,
                                          const ReportOptions& options,
                                          std::vector<std::string>& warnings);

}  // namespace binpick::eval
