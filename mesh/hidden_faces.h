// Faces hidden inside a coplanar overlap. Face F is hidden when some face G lies in the same plane,
// faces the opposite way and covers F: the two face each other at zero distance, so F can neither
// see nor be seen. Two boxes touching face to face lose both contact faces (each covers the other);
// a block standing on the floor loses its bottom, while the floor stays (the bottom does not cover
// it). Faces that overlap with the same orientation (a light lying in the ceiling plane) are left
// alone: that is a modelling question, not hidden geometry. Coplanar means every corner within tol
// of the other face's plane, and that face planar within tol.
// Caveat: locally, a two-sided sheet written as two coincident faces back to back looks exactly
// like two touching boxes, so it loses both faces too; model thin sheets with some thickness.
#pragma once

#include <vector>

#include "mesh/clean_faces.h"

namespace radfarm {

// tol: distance within which corners count as in G's plane and inside G's outline.
std::vector<bool> FindHiddenFaces(const std::vector<CleanFace>& faces, double tol);

}  // namespace radfarm
