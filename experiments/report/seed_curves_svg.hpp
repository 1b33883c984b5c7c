// A cell's drill-down figure in the HTML report: every seed's evaluation curve (return against
// env steps) as one line, drawn as inline SVG so the page needs no script or network to show it.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "experiments/report/report_folder.hpp"

namespace rapid {

// The colour of a seed's line and of its swatch in the seed table: the i-th seed of the grid.
std::string seed_colour(std::size_t index);

// An <svg class="seed-curves"> with one polyline per seed, coloured as `colours` says (seed →
// colour), and the step and return ranges at its axes. Empty when no seed has a curve.
std::string seed_curves_svg(const std::map<std::uint64_t, SeedCurve>& curves,
                            const std::map<std::uint64_t, std::string>& colours);

}  // namespace rapid
