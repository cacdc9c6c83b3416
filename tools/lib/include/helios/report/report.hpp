#pragma once
// report.md: a run as a document a reviewer can sign off (tools/lib/src/report/README.md). The
// problem in words, the spec as a table with units, the derivation as mathematics (LaTeX in $...$ /
// $$...$$, compact: symbolic::Typesetter), helios-verify's verdict beside each condition it
// checked, the solution (status, objective, residual, switches, the search record) and the plots.
#include <optional>
#include <string>

#include "helios/io/json_io.hpp"

namespace helios::report {

// The artifacts of one run, already read (schema-valid for the builtin backend; a model's
// derivation is read as verify reads it). Sources name the files in the report.
struct ReportInputs {
  std::string problem_text;  // the problem in words (scenarios/SNN/problem.txt)
  io::json spec, derivation;
  std::optional<io::json> verify, solution;  // a report before verifying or solving omits them
  std::string derivation_source = "derivation.json";
};

// Text from an artifact as Markdown that stays text: every character that opens markup in
// Markdown or pandoc's extensions (math, raw TeX, code, emphasis, links, HTML and entities,
// sub/superscript, citations, table cells) is backslash-escaped, and a line break or other control
// character becomes a space, so a string cannot open math, a code span, a link, an HTML element or
// a new line (a new table row) of the document. The report's and the scoreboard's escape.
std::string markdown_text(const std::string& text);

// The Markdown text. Throws input_error naming the derivation field an expression of which cannot
// be read (an expression the verifier could not read either is shown as its text instead).
std::string report_markdown(const ReportInputs& in);

}  // namespace helios::report
