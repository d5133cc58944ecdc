// trispline::core mass-spring relaxation of the contact surface S(u,v) = F(u,v,0) (seed §2.3.2).
//
// Model (seed §2.3.2): every control point P_ij of S (l×m grid) is a mass M connected to its (up to) four grid
// neighbours P_i±1,j and P_i,j±1 by springs of stiffness k. Force on mass i:
//     F_i = k·Σ_n (|D_in| − L_in)·D_in/|D_in| − ρ·v_i,     D_in = P_n − P_i,
// with zero rest length L_in = 0 by default (then the spring term is simply k·D_in), or L_in = the initial
// neighbour distance (SpringParams::rest_length_initial). The damping force −ρ·v (ρ ≥ 0) is the seed's "+ρ·v,
// ρ typically negative" with the sign folded in. Each mass has ONE degree of freedom: it moves only along its own
// unit direction V_P (the extrusion direction V for F1 or the surface normal for F2); only the component
// a_i = <F_i/M, V_P> is used. Its state is the scalar offset s_i along V_P from its initial position:
// P_i = P_i⁰ + s_i·V_P.
//
// Integration: symplectic (semi-implicit) Euler, v ← v + dt·a(s, v); s ← s + dt·v, all masses updated from the
// same old state (Jacobi order, deterministic, no threads). Time step rule:
//     ω_max = sqrt(8k/M)            (Gershgorin bound of the projected 4-neighbour stiffness: 4k + 4·k·|V_i·V_n|)
//     dt    = min(1/ω_max, M/ρ)     (= 0.5·2/ω_max, and ρ·dt/M ≤ 1)
// For the damped oscillator this keeps the symplectic-Euler amplification matrix stable (needs (ω·dt)² < 4 − 2ρdt/M
// and ρdt/M < 2; both hold with margin). With rest lengths of compressed springs the bound is not strict.
// Overdamped regime: when ρ ≥ sqrt(8kM), dt = M/ρ and the velocity carries no memory (v = F/ρ each step), so a step
// is a Jacobi gradient-flow step s ← s + (M/ρ²)·F with kM/ρ² ≤ 1/8; for zero rest length and parallel V_P this is a
// convex combination of neighbours (discrete maximum principle): no mass rises above the highest initial/floor
// level, so masses resting on supports stay there. With lighter damping, inertia can overshoot and lift the whole
// sheet off its supports: the seed model has no gravity, and a free zero-rest-length sheet is in equilibrium at any
// height. Use ρ ≥ sqrt(8kM) for placement.
//
// Collision (seed: "collision detection prevents the masses from penetrating the scene"): per mass a support floor
// is precomputed once: a ray from P_i⁰ + H·V_P (H = SpringParams::ray_height, world units) in direction −V_P is cast
// against `scene` (the scene WITHOUT the placed object); the first hit gives floor_i = <hit − P_i⁰, V_P>. During the
// simulation s_i is clamped to ≥ floor_i and, when clamped, its velocity is zeroed if it points into the floor
// (masses can still lift off). A miss (or scene == nullptr / empty) means no floor. Note: "first hit from above"
// means a mass under an overhang gets the overhang's top as its floor (it is pushed out on top).
//
// Termination (seed: local roughness): at each mass, the cross products of consecutive neighbour vectors in cyclic
// order (+u, +v, −u, −v) are the normals of the (up to 4) triangles around it; the mass is "rough" when the angle
// between any two cyclically consecutive existing normals exceeds `angle_threshold_deg`. Boundary masses use the
// triangles they have (edge: 2 triangles, 1 angle; corner: 1 triangle, always smooth); degenerate (zero) normals
// are skipped. Candidates = rough masses at the start; the active set = masses within `neighbourhood` grid steps
// (Chebyshev distance in (i,j)) of a candidate, or all masses when neighbourhood < 0. Only active masses move;
// the others are fixed anchors (their springs still act). Before every step (step 0 included) the active masses'
// roughness is checked: none rough → converged, stop. Otherwise stop after max_steps steps (converged = false).
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace trispline::core {

class RayCaster;

struct SpringParams {
  double mass = 1.0;                 // M > 0 (mass units)
  double stiffness = 100.0;          // k > 0 (force per world unit)
  double damping = 30.0;             // ρ ≥ 0 (force per unit velocity); damping force = −ρ·v (≥ sqrt(8kM))
  bool rest_length_initial = false;  // false: zero rest length (seed); true: rest length = initial distance
  double angle_threshold_deg = 2.0;  // roughness threshold, in (0, 180) degrees
  int neighbourhood = -1;            // grid steps around candidates that move; < 0: all masses move
  int max_steps = 20000;             // ≥ 0
  double ray_height = 100.0;         // H > 0, world units: floor rays start at P⁰ + H·V_P
};

struct SpringStats {
  int steps = 0;                  // integration steps taken
  bool converged = false;         // all active masses smooth (roughness ≤ threshold) when it stopped
  double max_displacement = 0.0;  // max over masses of |s_i| = |P_i − P_i⁰|, world units
  double dt = 0.0;                // the time step used
  int candidates = 0;             // rough masses at the start
  int active = 0;                 // masses allowed to move
  int floors = 0;                 // masses whose floor ray hit the scene
};

// Relaxes `points` in place. points #(l·m), index i + l·j (u fastest), world units; directions #(l·m) unit V_P
// (|V_P| within 1e-6 of 1). scene may be nullptr (no collision); if not null it must be committed.
// Deterministic: fixed iteration order, sequential single-ray queries.
// Throws std::invalid_argument on: l < 1 or m < 1, size mismatches, non-finite points/directions, non-unit
// directions, mass ≤ 0, stiffness ≤ 0, damping < 0 (or non-finite), threshold outside (0, 180), max_steps < 0,
// ray_height ≤ 0.
SpringStats relax_contact_surface(std::vector<glm::dvec3>& points, int l, int m,
                                  const std::vector<glm::dvec3>& directions, const RayCaster* scene,
                                  const SpringParams& params);

// Largest angle (degrees) between consecutive triangle normals around mass (i, j) — the roughness used above.
double contact_roughness_deg(const std::vector<glm::dvec3>& points, int l, int m, int i, int j);

}  // namespace trispline::core
