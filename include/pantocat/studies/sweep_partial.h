#pragma once

#include <pantocat/studies/sweep_study.h>

#include <map>
#include <string>

namespace pantocat
{
/// The version of pantocat-fem that writes and resumes partial files ("0.1.0").
const std::string& program_version();

/**
 * The start of a sweep's <name>.csv.partial: a line with the program
 * version, one line "# set Subsection/Entry = value" per parameter the runs
 * are made from (SweepPlan::parameters), and the CSV's header line. A resume
 * compares them with its own: rows of another version or of other parameters
 * are never mixed with its own.
 */
std::string partial_file_start(const SweepPlan& plan);

/**
 * One finished run as it is appended to the partial file: its rows, then a
 * line "# end of run: <n> rows, CRC-32 <8 hex digits>" over exactly those
 * rows. A run counts as finished only with this line, so a run whose append
 * was cut (a kill, a full disk) runs again.
 */
std::string partial_record(const std::string& rows);

/// What a partial file gives a resumed sweep.
struct PartialRuns
{
  std::map<unsigned int, std::string> rows; ///< per finished run (plan index), its rows
  /// Lines at the end that a stop cut short (no end line yet): dropped, their run
  /// runs again.
  unsigned int dropped_lines = 0;
};

/**
 * Reads the partial file @p text (named @p file in messages) of a sweep with
 * @p plan. Accepted: every run whose record is complete (its end line, with
 * the count and CRC-32 of its rows) and valid row by row: the fields of a row
 * (the key columns, pantograph, the 15 figures, status, quoted reason), a
 * key of a run of @p plan, each figure empty or a finite number, status
 * completed (figures, no reason), failed or refused (no figures, a reason),
 * one row per pantograph of the run with increasing numbers. Dropped: what
 * follows the last complete record, as a stopped sweep leaves it (rows of
 * one run without their end line, a last line without its newline); its
 * complete lines must still be valid rows. Everything else throws an
 * InputError "Sweep/Resume = true: <file>, line <n>: <what is wrong>; ...",
 * the file left as it is: another version or other parameters, another
 * header, a broken or changed row, a second record of a run.
 */
PartialRuns read_partial_file(const std::string& text, const std::string& file,
                              const SweepPlan& plan);
} // namespace pantocat
