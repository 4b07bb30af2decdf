// index.html for a folder of review movies: every movie as an HTML5 <video> with its contact sheet and
// its movement's plot. Only files that exist are linked (relative to the page).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/review/movie_set.h"

namespace stirrup::render {

// Writes DIR/index.html (via a temporary name) and returns its path.
std::filesystem::path writeIndexPage(const std::filesystem::path& dir, const std::vector<MovieResult>& movies,
                                     const std::string& title = "stirrup review movies");

// Escapes &, <, >, " and ' for HTML and XML text and attributes (' as &#39;, which both read): the review
// page, and check's JUnit, HTML and SVG reports.
std::string htmlEscape(const std::string& s);

}  // namespace stirrup::render
