#pragma once
// Step-over for a ball-end cutter and a target scallop height (docs/METHOD.md §2). All lengths
// in mm. rho is the signed radius of normal curvature of the design surface across the
// passes: > 0 convex, < 0 concave, infinite (use the flat functions) for a plane; the ball
// gouges unless |rho| > r.
//
// The curved forms use x = h(2r - h) / (2(rho + r)(rho + h)) = 1 - cos(alpha), alpha the
// half-angle between neighbouring contact points seen from the centre of curvature, which
// stays accurate for any |rho| (Loney & Ozsoy's equivalent form cancels catastrophically for
// large |rho| and is not used).

namespace subfeed::geometry {

// Flat surface: distance between neighbouring passes, and its inverse.
[[nodiscard]] double flat_step(double ball_radius, double scallop);
[[nodiscard]] double flat_scallop(double ball_radius, double step);

// Curved surface: chord between neighbouring contact points on the design surface for a
// scallop h, and its inverse. In a hollow barely wider than the ball (x > 1) the step is
// the hollow's whole contact circle, 2|rho|.
[[nodiscard]] double contact_step(double ball_radius, double scallop, double rho);
[[nodiscard]] double contact_scallop(double ball_radius, double step, double rho);

// The same spacing between neighbouring ball centres (on the CL surface): farther apart on
// convex, closer on concave surfaces.
[[nodiscard]] double cl_step(double ball_radius, double scallop, double rho);

// Distance between slicing planes for a CL spacing, given the slope of the CL surface
// across the planes: s_dot_n is the dot product of the planes' unit normal and the unit
// surface normal.
[[nodiscard]] double plane_interval(double cl_spacing, double s_dot_n);

} // namespace subfeed::geometry
