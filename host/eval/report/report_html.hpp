// report.html: one page with the summary table (precision at both operating points, median
// errors, time per hypothesis, the score calibration), the precision figure, the precision
// against score threshold and the pictures, all by relative path.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/eval/eval_run.hpp"
#include "host/eval/report/report_pictures.hpp"

namespace binpick::eval {

std::string report_html(const std::vector<DatasetEvaluation>& evaluations,
                        const EvalOptions& options, const ReportFiles& files,
                        const std::vector<PicturedImage>& pictures);

void write_report_html(const std::filesystem::path& path,
                       const std::vector<DatasetEvaluation>& evaluations,
                       const EvalOptions& options, const ReportFiles& files,
                       const std::vector<PicturedImage>& pictures);

// s with & < > " escaped.
std::string html_escaped(const std::string& s);

}  // namespace binpick::eval
