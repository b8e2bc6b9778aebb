// wrapAtSeparator / wrapPieces (demos/draw/figure_style.h): the one line-filling of the figures —
// number blocks, contact sheets and `cdlab check`'s captions (which cut a piece wider than a line).
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "demos/draw/figure_style.h"
#include "render/canvas.h"
#include "tests/gl_test_context.h"

using namespace cdlab;
using namespace cdlab::demos;

TEST_CASE("wrapAtSeparator: lines within the width, broken at spaces, a wide word cut between characters") {
    const render::Canvas c(test::glContext(), {320, 120, 1, 4});
    const render::TextStyle style{17, render::roleColor(render::Role::Ink), render::Anchor::TopLeft, false, false};
    const std::string text = "yours reaches −1.74 along it, A − B reaches −0.34; your a is not extreme in A";
    const std::vector<std::string> lines = wrapAtSeparator(c, text, " ", style, 200, true);
    REQUIRE(lines.size() >= 3);
    std::string joined;
    for (const std::string& line : lines) {
        CHECK(c.measureText(line, style).x() <= 200);
        joined += (joined.empty() ? "" : " ") + line;
    }
    CHECK(joined == text);  // every word kept, none cut
    CHECK(wrapAtSeparator(c, text, " ", style, 1e6, true) == std::vector<std::string>{text});
    // A word wider than the line: cut between characters, never inside a UTF-8 sequence.
    const std::string wide = "λλλλλλλλλλλλλλλλλλλλ";
    const std::vector<std::string> cut = wrapAtSeparator(c, wide, " ", style, 60, true);
    REQUIRE(cut.size() > 1);
    std::string whole;
    for (const std::string& piece : cut) {
        CHECK(c.measureText(piece, style).x() <= 60);
        CHECK(piece.size() % 2 == 0);  // whole two-byte characters
        whole += piece;
    }
    CHECK(whole == wide);
    // Without cutting (number blocks: a token is never split), the wide word keeps a line of its own.
    CHECK(wrapAtSeparator(c, "a " + wide + " b", " ", style, 60) == std::vector<std::string>{"a", wide, "b"});
}
