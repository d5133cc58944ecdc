// trispline::core contact grid helpers for sketch placement: filling rays that missed, contact-surface
// parameters (seed §2.3.1: arc length in v, chord length along the middle column in u).
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace trispline::core {

// Fills the unknown entries of an nu×nv grid (u fastest, index i + nu·j) of view depths in passes: each unknown
// entry with known 4-neighbours takes their mean; all entries found in one pass are committed together, so the
// result does not depend on visiting order. Repeats until full (the grid is 4-connected, so every pass fills at
// least one entry while one is known: no 8-neighbour rule is needed).
// known #(nu·nv) (1 = known). Returns the number of passes. Requires at least one known entry (else no-op, -1).
int fill_missing_depths(std::vector<double>& depth, const std::vector<unsigned char>& known, int nu, int nv);

// v parameters (#nv): chord length along each cross-section (row i fixed, j = 0..nv−1) averaged over the nu rows.
std::vector<double> contact_params_v(const std::vector<glm::dvec3>& grid, int nu, int nv);
// u parameters (#nu): chord length along the middle column (j = nv/2; the midpoint of the two middle columns when
// nv is even).
std::vector<double> contact_params_u(const std::vector<glm::dvec3>& grid, int nu, int nv);

}  // namespace trispline::core
