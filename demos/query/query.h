// `cdlab query`: JSON Lines in, one JSON answer per line out (format: README, "cdlab query").
#pragma once

#include <iosfwd>
#include <string>

#include "demos/scene/json_reader.h"

namespace cdlab::demos {

/// Answers one query line (never throws: errors become {"id":...,"error":"..."}).
Json answerQuery(const std::string& line);

/// Reads queries until EOF; returns 1 if any line failed, else 0. Blank lines are skipped.
int runQueries(std::istream& in, std::ostream& out);

}  // namespace cdlab::demos
