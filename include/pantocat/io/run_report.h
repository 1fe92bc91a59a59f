#pragma once

#include <pantocat/io/run_summary.h>

#include <string>
#include <vector>

namespace pantocat
{
/// A picture of the report: an SVG file of the output directory and its caption.
struct ReportFigure
{
  std::string svg; ///< file name in the directory; left out if missing or empty
  std::string caption;
};

/**
 * report.html in @p directory: one self-contained page (HtmlReport) with what
 * an engineer reads of a completed run, in the field's words: the case (line,
 * spans, droppers, pantographs with their speed in km/h, start), per
 * pantograph the statistics of its evaluation window (raw and low pass) and
 * its assessment (value, limit, rule, pass or fail), the @p figures inline,
 * the events with their positions (whole-run extremes, dropper slack per
 * dropper, contact loss), the inputs the case set and the program's version.
 * Written atomically, as summary.json.
 */
void write_run_report(const std::string& directory, const RunRecord& record,
                      const std::vector<ReportFigure>& figures);
} // namespace pantocat
