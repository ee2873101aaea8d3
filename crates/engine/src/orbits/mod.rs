//! Periodic orbits of the impact map, their stability and their bifurcations.
//!
//! * [`fixed`]: the (1, k) solutions (one bounce every k periods), their Jacobian,
//!   eigenvalues and classification, and the α interval on which a stable one exists
//!   (its birth and its period-doubling point α_PD).
//! * [`two_cycle`](mod@two_cycle): the (2, 2k) solutions near a (1, k) one, solved exactly by Newton's
//!   method, the asymptotic approximation near the period-doubling point (the paper's
//!   printed one and the corrected one), and the border collision of the branch.
//! * [`periodic`]: (n, k) cycles of the exact map by Newton's method on n steps of it,
//!   with their multipliers; every accepted point returns within 1e-11.
//! * [`continuation`]: pseudo-arclength continuation of cycles in α with period
//!   doubling, fold, border collision, grazing and window exits
//!   located, and branch switching onto doubled branches ([`continuation::branches`]).
//! * [`curves`]: two-parameter curves of period doublings, folds, border collisions
//!   and grazings over (α, r) or (α, D), with their codimension-two points and the
//!   flip's criticality.
//! * [`events`]: the special points of a branch (PD, fold, border collision, grazing,
//!   window exit) and the helpers that locate them.
//! * [`cascade`]: the period-doubling cascade from a (1, k) solution: α₁ < α₂ < …, how
//!   each 2ⁿ branch ends, and the Feigenbaum ratios.
//! * [`certify`]: proofs by interval arithmetic that an exact (n, k) cycle lies in a
//!   small box (the Krawczyk test on the cycle's equations, each landing shown to be
//!   its flight's first contact), with its stability where the multipliers' enclosure
//!   decides it.
//! * [`scaling`]: the power laws ΔT ∝ Δκ and Δt ∝ Δκ^½ near the period-doubling point
//!   (the paper's Fig. 4 and Fig. 5), from exact solutions and from simulated orbits.
//!
//! Everything here is pure and synchronous like the rest of the engine. Functions that
//! the terminal application calls per frame (e.g. [`fixed::stability_window`]) do
//! bounded work and never panic.

pub mod border;
pub mod cascade;
pub mod certify;
pub mod continuation;
pub mod curves;
pub mod events;
pub mod fixed;
pub mod manifold;
pub mod periodic;
pub(crate) mod roots;
pub mod scaling;
pub mod two_cycle;

pub use fixed::{
    alpha_at_delta_kappa, fixed_point_slope, fixed_points, stability_window, stability_windows,
    Classification, FixedPoint, StabilityWindow, WindowEnd,
};
pub use two_cycle::{
    approximation_corrected, approximation_paper, border_collision, map_check, two_cycle,
    two_cycle_at, Approximation, BorderCollision, NoBorderCollision, NoTwoCycle, TwoCycle,
};
