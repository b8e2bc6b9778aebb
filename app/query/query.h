// `cdlab query`: JSON Lines in, one JSON answer per line out (format: docs/query.md).
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>

#include "app/scene/json_reader.h"

namespace cdlab::demos {

/// Answers one query line (never throws: errors become {"id":...,"error":"..."}; a line the strict
/// reader refuses keeps its "id" when the line is JSON, read while streaming: no tree is built for it).
Json answerQuery(const std::string& line);
/// The same, the error naming the input line: "query: line N: ...".
Json answerQuery(const std::string& line, std::size_t lineNumber);

/// Reads queries until EOF; returns 1 if any line failed, else 0. Blank (whitespace-only) lines are
/// skipped: they are not queries, and every answer carries its query's "id". A line whose answer
/// throws (std::bad_alloc) answers an error; the lines after it are still answered.
int runQueries(std::istream& in, std::ostream& out);

}  // namespace cdlab::demos
